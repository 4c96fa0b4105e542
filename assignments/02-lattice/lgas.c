/* YOUR FILE — this is the file you fill in for stage 02-lattice.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/02-lattice/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=02`; see your own code at work with
 * `make lesson STAGE=02`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* lgas.c — the HPP and FHP lattice gases: collision table, propagation, collision
 * (graded). */
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/bits.h"
#include "lz/lattice.h"
#include "lz/lgas.h"


/* A state collides when it is symmetric under a half turn (head-on pairs and their
 * hole duals) or a third of a turn (the symmetric triples): then it turns by ±60°. */
void lz_lgas_table(lz_lgas_model model, uint8_t table[LZ_LGAS_TABLE_SIZE])
{
	/* Hint: loop over c in {0, 1} and s in [0, 64). FHP: s collides when
	 * lz_site_rotate(s, 3) == s (a head-on pair, or four particles with a head-on pair
	 * of holes) or lz_site_rotate(s, 2) == s (the triples {0,2,4}, {1,3,5}); it then
	 * becomes lz_site_rotate(s, c ? -1 : +1). The empty and the full site satisfy both
	 * tests and turn into themselves. HPP uses four bits: only 0x5 <-> 0xA change.
	 * See lessons/02-lattice/README.md §7. */
	LZ_TODO();
}

/* Pull form: bit k of the new site r comes from the old site r - e_k. */
void lz_lgas_propagate(lz_lgas *g)
{
	/* Hint: for every site (x, y) and direction k, the particle that arrives moving in
	 * direction k left the site (x - dx_k, y - dy_k) (lz_lattice_dirs of
	 * lz_lgas_lattice(g->model)), wrapped with & g->mask: next = (old & LZ_LGAS_WALL) |
	 * OR over k of (site[from] & (1 << k)). Write into g->next, then swap the pointers.
	 * A wrong sign sends particles backwards; a forgotten mask reads outside the array.
	 * See lessons/02-lattice/README.md §7. */
	LZ_TODO();
}

/* Table look-up with a random chirality per site; walls bounce back. */
void lz_lgas_collide(lz_lgas *g, const uint8_t table[LZ_LGAS_TABLE_SIZE], gsl_rng *rng)
{
	/* Hint: size_t n = (size_t)g->side * g->side sites. Keep a word of random bits,
	 * bits = gsl_rng_get(rng), refilled every 32 sites when gsl_rng_max(rng) is
	 * 0xFFFFFFFF (else take gsl_rng_uniform_int(rng, 2) per site). A site with
	 * LZ_LGAS_WALL keeps the wall bit and has every particle reversed (rotate by 3 of 6
	 * for FHP, by 2 of 4 for HPP); any other s becomes table[(c << 6) | s]. Use a
	 * fresh chirality per site: one bit for the whole lattice makes the flow chiral.
	 * See lessons/02-lattice/README.md §7. */
	LZ_TODO();
}
