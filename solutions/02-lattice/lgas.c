/* lgas.c — the HPP and FHP lattice gases: collision table, propagation, collision
 * (graded). */
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/bits.h"
#include "lz/lattice.h"
#include "lz/lgas.h"

/* LZ_HELPERS_BEGIN */
/* The four HPP bits turned by k·90° counterclockwise. */
static unsigned hpp_rotate(unsigned s, int k)
{
	s &= 0xFu;
	k &= 3;
	return ((s << k) | (s >> (4 - k))) & 0xFu;
}
/* LZ_HELPERS_END */

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
	/* LZ_SOLUTION_BEGIN */
	for (unsigned c = 0; c < 2; c++)
		for (unsigned s = 0; s < 64; s++) {
			unsigned out = s;
			if (model == LZ_LGAS_FHP) {
				if (lz_site_rotate(s, 3) == s || lz_site_rotate(s, 2) == s)
					out = lz_site_rotate(s, c ? -1 : 1);
			} else if (s == 0x5u || s == 0xAu) {
				out = hpp_rotate(s, 1);
			}
			table[c << 6 | s] = (uint8_t)out;
		}
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	int n;
	const lz_site *e = lz_lattice_dirs(lz_lgas_lattice(g->model), &n);
	const uint32_t m = (uint32_t)g->mask;
	const int sh = g->shift;
	for (uint32_t y = 0; y <= m; y++) {
		uint8_t *out = g->next + (y << sh);
		const uint8_t *here = g->site + (y << sh);
		for (uint32_t x = 0; x <= m; x++)
			out[x] = (uint8_t)(here[x] & LZ_LGAS_WALL);
		for (int k = 0; k < n; k++) {
			const uint8_t bit = (uint8_t)(1u << k);
			const uint8_t *from = g->site + (((y - (uint32_t)e[k].y) & m) << sh);
			const uint32_t dx = (uint32_t)e[k].x;
			for (uint32_t x = 0; x <= m; x++)
				out[x] |= from[(x - dx) & m] & bit;
		}
	}
	uint8_t *t = g->site;
	g->site = g->next;
	g->next = t;
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	size_t n = (size_t)g->side * (size_t)g->side;
	int word = gsl_rng_max(rng) == 0xFFFFFFFFul && gsl_rng_min(rng) == 0;
	unsigned long bits = 0;
	int left = 0;
	for (size_t i = 0; i < n; i++) {
		unsigned s = g->site[i], c;
		if (word) {
			if (left == 0) {
				bits = gsl_rng_get(rng);
				left = 32;
			}
			c = (unsigned)(bits & 1u);
			bits >>= 1;
			left--;
		} else {
			c = (unsigned)gsl_rng_uniform_int(rng, 2);
		}
		if (s & LZ_LGAS_WALL)
			s = LZ_LGAS_WALL | (g->model == LZ_LGAS_FHP ? lz_site_reverse(s)
			                                             : hpp_rotate(s, 2));
		else
			s = table[c << 6 | (s & LZ_SITE_MASK)];
		g->site[i] = (uint8_t)s;
	}
	/* LZ_SOLUTION_END */
}
