/* test_pedmd.c — stage 06, the optimistic parallel engine (lz/pedmd.h): who owns a
 * cell, the class of every cell, who must hear of a change, an event on a rank, a
 * message that arrives, state saving, the verdict at a cut and the balanced cuts; then
 * whole runs, which must commit the serial run's events bit for bit.
 *
 * The references are the test's own: owners, classes and listeners by brute force
 * over cell coordinates (not through lz_edmd_block_of); the serial engine of stage 05
 * stepped by hand for the events and the records; exact floating-point cases for the
 * verdict; every placement of the cuts for the balance. The scenes of the unit tests
 * are built by hand: a box of 6 × 6 cells of side 2, cut into two slabs of three rows
 * (rank 0: y < 6, rank 1: y >= 6), with one or two particles placed so that the next
 * event is known in closed form. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/edmd.h"
#include "lz/pedmd.h"
#include "lz/rng.h"
#include "lztest.h"

static const lz_pedmd_params PARAMS = {0.05, 0.5, 0, 0.1, 1, 16, 0, 1.125, 0};

/* ---- systems ---- */

/* n particles on a lattice at packing eta, started; re-based only when asked. */
static lz_edmd *gas(int dim, size_t n, double eta, int walls, double g, double restitution,
                    unsigned long seed)
{
	lz_edmd_params p = {dim, n, eta, restitution, g, walls, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	LZ_REQUIRE(e, "lz_edmd_alloc(%dD, N = %zu, η = %g): %s", dim, n, eta, lz_error_message());
	lz_rng *rng = lz_rng_alloc("mt19937", seed);
	LZ_REQUIRE(rng && lz_edmd_place_lattice(e, rng) == LZ_OK, "placing %zu particles: %s", n,
	      lz_error_message());
	lz_rng_free(rng);
	e->rebase_auto = 0;
	return e;
}

/* A box of side L with m cells a side (walls as lz_edmd_params) and n particles placed
 * at r with velocities v (3 numbers each), started. */
static lz_edmd *placed(int dim, int m, double L, int walls, size_t n, const double *r,
                       const double *v)
{
	double v1 = dim == 3 ? M_PI / 6 : M_PI / 4;
	lz_edmd_params p = {dim, n, (double)n * v1 / pow(L, dim), 1, 0, walls, m, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	LZ_REQUIRE(e, "lz_edmd_alloc(%dD box of side %g, %d cells a side): %s", dim, L, m,
	      lz_error_message());
	LZ_REQUIRE(e->m[0] == m && fabs(e->L - L) < 1e-9, "the box came out %g wide with %d cells",
	      e->L, e->m[0]);
	LZ_REQUIRE(lz_edmd_set(e, r, v) == LZ_OK, "placing the particles: %s", lz_error_message());
	e->rebase_auto = 0;
	return e;
}

/* The slabs of the unit tests: 6 × 6 cells of side 2 (L = 12), periodic. */
static lz_edmd *slabs(size_t n, const double *r, const double *v)
{
	return placed(2, 6, 12, LZ_EDMD_WALLS_NONE, n, r, v);
}

/* ---- ranks on the stub ---- */

typedef struct {
	int P;
	lz_stub *stub;
	lz_pedmd_domains *d;
	lz_pedmd *r[8];
} team;

/* P ranks of system s along `kind`, messages delivered at once, each rank's window
 * begun and open to the end of time. */
static team team_new(const lz_edmd *s, int P, int kind)
{
	team q = {P, NULL, NULL, {NULL}};
	lz_stub_params sp = {P, LZ_STUB_ROUND_ROBIN, 1, 0, 0, 1, 1e-6, 1e-6, 1e-6};
	q.stub = lz_stub_alloc(&sp);
	q.d = q.stub ? lz_pedmd_domains_alloc(s, P, kind) : NULL;
	LZ_REQUIRE(q.d, "a stub of %d ranks and its domains: %s", P, lz_error_message());
	for (int k = 0; k < P; k++) {
		q.r[k] = lz_pedmd_alloc(s, q.d, lz_stub_rank(q.stub, k), &PARAMS);
		LZ_REQUIRE(q.r[k], "lz_pedmd_alloc of rank %d: %s", k, lz_error_message());
		LZ_REQUIRE(lz_pedmd_begin(q.r[k], INFINITY) == LZ_OK, "a window on rank %d", k);
	}
	return q;
}

static void team_free(team *q)
{
	for (int k = 0; k < q->P; k++)
		lz_pedmd_free(q->r[k]);
	lz_pedmd_domains_free(q->d);
	lz_stub_free(q->stub);
}

/* Two particles in the slabs, twice: the serial run (a) and its two ranks (q). */
typedef struct {
	lz_edmd *s, *a;
	team q;
} duo;

static duo duo_new(const double *r, const double *v)
{
	duo d = {slabs(2, r, v), slabs(2, r, v), {0, NULL, NULL, {NULL}}};
	d.q = team_new(d.s, 2, LZ_PEDMD_ROWS);
	return d;
}

/* The next serial event, and the next event of rank k. */
static void duo_step(duo *d, int k, int *did)
{
	lz_edmd_step(d->a);
	LZ_REQUIRE(lz_pedmd_step(d->q.r[k], did) == LZ_OK, "rank %d's step: %s", k, lz_error_message());
}

static void duo_free(duo *d)
{
	team_free(&d->q);
	lz_edmd_free(d->s);
	lz_edmd_free(d->a);
}

/* The next message that has arrived at rank r: 1, or 0 when none has. */
static int take(lz_pedmd *r, lz_pedmd_message *m)
{
	int from;
	size_t n;
	int got = lz_msg_poll(r->msg, &from, m, sizeof *m, &n);
	LZ_REQUIRE(got >= 0 && (got == 0 || n == sizeof *m), "polling rank %d: %s", r->rank,
	      lz_error_message());
	return got;
}

/* The messages rank `to` has waiting, drained: how many of each kind (STATE, MIGRATE,
 * LEAVE), the last one in *last. */
static void drain(lz_pedmd *to, int count[3], lz_pedmd_message *last)
{
	count[0] = count[1] = count[2] = 0;
	lz_pedmd_message m;
	while (take(to, &m)) {
		LZ_REQUIRE(m.kind <= LZ_PEDMD_LEAVE, "a message of kind %u", m.kind);
		count[m.kind]++;
		*last = m;
	}
}

static int same_particle(const lz_edmd_particle *a, const lz_edmd_particle *b)
{
	return memcmp(a->r, b->r, sizeof a->r) == 0 && memcmp(a->v, b->v, sizeof a->v) == 0 &&
	       a->t0 == b->t0 && a->count == b->count && a->cell == b->cell;
}

/* 1 when particle i is in the list of cell c. */
static int in_cell(const lz_edmd *e, uint32_t i, uint32_t c)
{
	for (int32_t j = e->list[c].head; j >= 0; j = e->next[j])
		if ((uint32_t)j == i)
			return 1;
	return 0;
}

/* ---- brute force over cell coordinates ---- */

static void coords(const lz_edmd *e, uint32_t c, int x[3])
{
	x[0] = (int)(c % (uint32_t)e->m[0]);
	x[1] = (int)(c / (uint32_t)e->m[0] % (uint32_t)e->m[1]);
	x[2] = (int)(c / ((uint32_t)e->m[0] * (uint32_t)e->m[1]));
}

/* The cells next to c (its 3^dim block less c; walls stop it, periodic axes wrap),
 * into nb[]; their number (repeats possible on a 3-cell axis, which is harmless). */
static int neighbours(const lz_edmd *e, uint32_t c, uint32_t *nb)
{
	int x[3], n = 0;
	coords(e, c, x);
	int span[3] = {1, 1, e->dim == 3 ? 1 : 0};
	for (int dz = -span[2]; dz <= span[2]; dz++)
		for (int dy = -span[1]; dy <= span[1]; dy++)
			for (int dx = -span[0]; dx <= span[0]; dx++) {
				int d[3] = {dx, dy, dz}, y[3], ok = dx || dy || dz;
				for (int a = 0; a < 3 && ok; a++) {
					y[a] = x[a] + d[a];
					if (y[a] < 0 || y[a] >= e->m[a]) {
						ok = !e->wall[a];
						y[a] = (y[a] + e->m[a]) % e->m[a];
					}
				}
				if (ok)
					nb[n++] = (uint32_t)(y[0] + e->m[0] * (y[1] + e->m[1] * y[2]));
			}
	return n;
}

/* The owner of c by looking at every rank's run of the curve. */
static int owner_by_search(const lz_pedmd_domains *d, uint32_t c)
{
	for (int r = 0; r < d->P; r++)
		if (d->cut[r] <= d->place[c] && d->place[c] < d->cut[r + 1])
			return r;
	return -1;
}

static const char *class_name(int k)
{
	static const char *name[] = {"FAR", "HALO", "INTERIOR", "BORDER"};
	return k >= 0 && k < 4 ? name[k] : "not a class";
}

/* Domains of ncells cells by hand: the curve a random permutation, cuts as given. */
static lz_pedmd_domains *hand_domains(size_t ncells, int P, const uint32_t *cut, gsl_rng *g)
{
	lz_pedmd_domains *d = calloc(1, sizeof *d);
	LZ_REQUIRE(d, "out of memory");
	d->P = P;
	d->kind = LZ_PEDMD_ROWS;
	d->ncells = ncells;
	d->curve = malloc(ncells * sizeof *d->curve);
	d->place = malloc(ncells * sizeof *d->place);
	LZ_REQUIRE(d->curve && d->place, "out of memory");
	for (uint32_t k = 0; k < ncells; k++)
		d->curve[k] = k;
	for (size_t k = ncells; k-- > 1;) {
		size_t j = gsl_rng_uniform_int(g, k + 1);
		uint32_t t = d->curve[k];
		d->curve[k] = d->curve[j];
		d->curve[j] = t;
	}
	for (uint32_t k = 0; k < ncells; k++)
		d->place[d->curve[k]] = k;
	memcpy(d->cut, cut, (size_t)(P + 1) * sizeof *cut);
	return d;
}

/* ---- owner ---- */

LZ_TEST(owner_follows_the_cuts)
{
	/* five ranks over a shuffled curve of 20 cells, one rank with a single cell */
	gsl_rng *g = lz_test_rng(601);
	uint32_t cut[] = {0, 1, 5, 6, 13, 20};
	lz_pedmd_domains *d = hand_domains(20, 5, cut, g);
	for (uint32_t c = 0; c < 20; c++) {
		int want = owner_by_search(d, c), got = lz_pedmd_owner(d, c);
		LZ_REQUIRE(got == want, "cuts 0|1|5|6|13|20 along a shuffled curve: cell %u lies at "
		      "place %u, so rank %d owns it, not %d (the place on the curve decides, cut[r] <= "
		      "place < cut[r+1])", c, d->place[c], want, got);
	}
	lz_pedmd_domains_free(d);

	/* one rank owns everything; 256 ranks of one cell each */
	uint32_t one[] = {0, 7};
	d = hand_domains(7, 1, one, g);
	for (uint32_t c = 0; c < 7; c++)
		LZ_REQUIRE(lz_pedmd_owner(d, c) == 0, "one rank: cell %u is rank %d's", c,
		      lz_pedmd_owner(d, c));
	lz_pedmd_domains_free(d);
	uint32_t many[LZ_PEDMD_RANKS_MAX + 1];
	for (int r = 0; r <= LZ_PEDMD_RANKS_MAX; r++)
		many[r] = (uint32_t)r;
	d = hand_domains(LZ_PEDMD_RANKS_MAX, LZ_PEDMD_RANKS_MAX, many, g);
	for (uint32_t c = 0; c < LZ_PEDMD_RANKS_MAX; c++)
		LZ_REQUIRE(lz_pedmd_owner(d, c) == (int)d->place[c], "%d ranks of one cell each: cell %u "
		      "at place %u belongs to rank %u, not %d", LZ_PEDMD_RANKS_MAX, c, d->place[c],
		      d->place[c], lz_pedmd_owner(d, c));
	lz_pedmd_domains_free(d);
	gsl_rng_free(g);

	/* the Morton curve of 4 × 4 cells cut in four: each rank a 2 × 2 quadrant */
	double r[3] = {1, 1, 0}, v[3] = {1, 0, 0};
	lz_edmd *e = placed(2, 4, 8, LZ_EDMD_WALLS_NONE, 1, r, v);
	d = lz_pedmd_domains_alloc(e, 4, LZ_PEDMD_MORTON);
	LZ_REQUIRE(d, "Morton domains: %s", lz_error_message());
	for (uint32_t c = 0; c < 16; c++) {
		int x = (int)(c % 4), y = (int)(c / 4), want = 2 * (y / 2) + x / 2;
		LZ_REQUIRE(lz_pedmd_owner(d, c) == want, "4 × 4 cells along the Morton curve, four ranks: "
		      "cell (%d, %d) is in quadrant %d, owner says %d", x, y, want, lz_pedmd_owner(d, c));
	}
	lz_pedmd_domains_free(d);
	lz_edmd_free(e);
}
END_TEST

/* ---- classify ---- */

/* The classes of every cell for every rank against the brute force. */
static void check_classes(const lz_edmd *e, int P, int kind, const char *what)
{
	lz_pedmd_domains *d = lz_pedmd_domains_alloc(e, P, kind);
	LZ_REQUIRE(d, "%s: %s", what, lz_error_message());
	uint8_t *cls = malloc(e->ncells);
	uint32_t nb[27];
	LZ_REQUIRE(cls, "out of memory");
	for (int rank = 0; rank < P; rank++) {
		memset(cls, 0xaa, e->ncells);
		lz_pedmd_classify(e, d, rank, cls);
		for (uint32_t c = 0; c < e->ncells; c++) {
			int mine = owner_by_search(d, c) == rank, other = 0, touch = 0;
			int n = neighbours(e, c, nb);
			for (int k = 0; k < n; k++) {
				int o = owner_by_search(d, nb[k]) == rank;
				other |= !o;
				touch |= o;
			}
			int want = mine ? (other ? LZ_PEDMD_BORDER : LZ_PEDMD_INTERIOR)
			                : (touch ? LZ_PEDMD_HALO : LZ_PEDMD_FAR);
			int x[3];
			coords(e, c, x);
			LZ_REQUIRE(cls[c] == want, "%s, rank %d of %d: cell (%d, %d, %d) is %s, classify says "
			      "%s (owned: INTERIOR, or BORDER when a cell of its block is another rank's; "
			      "not owned: HALO when a cell of its block is owned, else FAR%s)", what, rank, P,
			      x[0], x[1], x[2], class_name(want), class_name(cls[c]),
			      e->wall[0] || e->wall[1] || e->wall[2] ? "; a wall cuts the block short" : "");
		}
	}
	free(cls);
	lz_pedmd_domains_free(d);
}

/* An empty grid of m cells a side, one particle in it. */
static lz_edmd *grid(int dim, int m, int walls)
{
	double r[3] = {1, 1, dim == 3 ? 1 : 0}, v[3] = {1, 0, 0};
	return placed(dim, m, 2.0 * m, walls, 1, r, v);
}

LZ_TEST(classify_marks_border_and_halo)
{
	struct {
		int dim, m, walls, P, kind;
		const char *what;
	} cases[] = {
		{2, 6, LZ_EDMD_WALLS_NONE, 3, LZ_PEDMD_ROWS, "2D, 6 × 6 periodic cells, slabs of two rows"},
		{2, 8, LZ_EDMD_WALLS_NONE, 2, LZ_PEDMD_ROWS, "2D, 8 × 8 periodic cells, slabs of four rows"},
		{2, 8, LZ_EDMD_WALLS_NONE, 4, LZ_PEDMD_MORTON, "2D, 8 × 8 periodic cells, Morton quadrants"},
		{2, 8, LZ_EDMD_WALLS_NONE, 5, LZ_PEDMD_MORTON, "2D, 8 × 8 periodic cells, Morton in five"},
		{2, 6, LZ_EDMD_WALLS_BOX, 2, LZ_PEDMD_ROWS, "2D, 6 × 6 cells in a box, two slabs"},
		{2, 8, LZ_EDMD_WALLS_BOX, 4, LZ_PEDMD_MORTON, "2D, 8 × 8 cells in a box, Morton quadrants"},
		{3, 4, LZ_EDMD_WALLS_NONE, 8, LZ_PEDMD_MORTON, "3D, 4³ periodic cells, Morton octants"},
		{3, 5, LZ_EDMD_WALLS_X, 3, LZ_PEDMD_MORTON, "3D, 5³ cells, walls on x, Morton in three"},
		{3, 4, LZ_EDMD_WALLS_BOX, 2, LZ_PEDMD_ROWS, "3D, 4³ cells in a box, two slabs"},
		{2, 4, LZ_EDMD_WALLS_NONE, 1, LZ_PEDMD_MORTON, "one rank"},
	};
	for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
		lz_edmd *e = grid(cases[k].dim, cases[k].m, cases[k].walls);
		check_classes(e, cases[k].P, cases[k].kind, cases[k].what);
		lz_edmd_free(e);
	}
}
END_TEST

/* ---- listeners ---- */

static void check_listeners(const lz_edmd *e, int P, int kind, const char *what)
{
	lz_pedmd_domains *d = lz_pedmd_domains_alloc(e, P, kind);
	LZ_REQUIRE(d, "%s: %s", what, lz_error_message());
	uint32_t nb[27];
	for (int rank = 0; rank < P; rank++)
		for (uint32_t c = 0; c < e->ncells; c++) {
			int want[LZ_PEDMD_RANKS_MAX] = {0}, nwant = 0;
			int n = neighbours(e, c, nb);
			nb[n++] = c;
			for (int k = 0; k < n; k++) {
				int o = owner_by_search(d, nb[k]);
				if (o != rank)
					want[o] = 1;
			}
			int out[32];
			for (int k = 0; k < 32; k++)
				out[k] = -7;
			int got = lz_pedmd_listeners(e, d, rank, c, out);
			for (int o = 0; o < P; o++)
				nwant += want[o];
			int x[3];
			coords(e, c, x);
			LZ_REQUIRE(got == nwant, "%s: rank %d, cell (%d, %d, %d): %d other ranks own a cell of "
			      "its block, listeners says %d (each once, never the rank itself)", what, rank,
			      x[0], x[1], x[2], nwant, got);
			for (int k = 0; k < got; k++) {
				LZ_REQUIRE(out[k] >= 0 && out[k] < P && want[out[k]] && out[k] != rank,
				      "%s: rank %d, cell (%d, %d, %d): listener %d is rank %d, which owns no "
				      "cell of the block (or is the rank itself)", what, rank, x[0], x[1], x[2],
				      k, out[k]);
				LZ_REQUIRE(k == 0 || out[k - 1] < out[k], "%s: rank %d, cell (%d, %d, %d): "
				      "listeners %d then %d — each once, in increasing order", what, rank,
				      x[0], x[1], x[2], out[k - 1], out[k]);
			}
		}
	lz_pedmd_domains_free(d);
}

LZ_TEST(listeners_are_the_other_owners_once_in_order)
{
	lz_edmd *e = grid(2, 6, LZ_EDMD_WALLS_NONE);
	check_listeners(e, 5, LZ_PEDMD_MORTON, "2D, 6 × 6 periodic cells, Morton in five");
	check_listeners(e, 3, LZ_PEDMD_ROWS, "2D, 6 × 6 periodic cells, three slabs");
	check_listeners(e, 1, LZ_PEDMD_ROWS, "one rank");
	lz_edmd_free(e);
	e = grid(3, 4, LZ_EDMD_WALLS_NONE);
	check_listeners(e, 8, LZ_PEDMD_MORTON, "3D, 4³ periodic cells, Morton octants");
	lz_edmd_free(e);
	e = grid(3, 4, LZ_EDMD_WALLS_BOX);
	check_listeners(e, 7, LZ_PEDMD_MORTON, "3D, 4³ cells in a box, Morton in seven");
	lz_edmd_free(e);
}
END_TEST

/* ---- save and restore ---- */

/* Everything of a rank that a window may change. */
typedef struct {
	size_t n;
	lz_edmd_particle *p;
	lz_edmd_event *ev;
	lz_pedmd_event *own, *ghost;
	double *heard, *key;
	uint8_t *role;
	double clock, now;
	uint64_t events, collisions, crossings;
} picture;

static picture take_picture(const lz_pedmd *r)
{
	const lz_edmd *e = r->e;
	size_t n = e->n;
	picture q = {n, malloc(n * sizeof *q.p), malloc(n * sizeof *q.ev), malloc(n * sizeof *q.own),
	             malloc(n * sizeof *q.ghost), malloc(n * sizeof *q.heard),
	             malloc(n * sizeof *q.key), malloc(n), r->clock, e->now, e->events,
	             e->collisions, e->crossings};
	LZ_REQUIRE(q.p && q.ev && q.own && q.ghost && q.heard && q.key && q.role, "out of memory");
	memcpy(q.p, e->p, n * sizeof *q.p);
	memcpy(q.ev, e->ev, n * sizeof *q.ev);
	memcpy(q.own, r->own, n * sizeof *q.own);
	memcpy(q.ghost, r->ghost, n * sizeof *q.ghost);
	memcpy(q.heard, r->heard, n * sizeof *q.heard);
	memcpy(q.role, r->role, n);
	for (uint32_t i = 0; i < n; i++)
		q.key[i] = lz_heap_contains(e->heap, i) ? lz_heap_key(e->heap, i) : INFINITY;
	return q;
}

static void free_picture(picture *q)
{
	free(q->p);
	free(q->ev);
	free(q->own);
	free(q->ghost);
	free(q->heard);
	free(q->key);
	free(q->role);
}

/* Rank r as picture q shows it, bit for bit, its cells and heap intact. */
static void check_picture(const lz_pedmd *r, const picture *q, const char *after)
{
	const lz_edmd *e = r->e;
	for (uint32_t i = 0; i < q->n; i++) {
		double key = lz_heap_contains(e->heap, i) ? lz_heap_key(e->heap, i) : INFINITY;
		LZ_REQUIRE(same_particle(&e->p[i], &q->p[i]), "%s: particle %u's record (position, "
		      "velocity, time, count, cell) is not what it was at the window's start", after, i);
		LZ_REQUIRE(memcmp(&e->ev[i], &q->ev[i], sizeof q->ev[i]) == 0 &&
		      memcmp(&r->own[i], &q->own[i], sizeof q->own[i]) == 0 &&
		      memcmp(&r->ghost[i], &q->ghost[i], sizeof q->ghost[i]) == 0,
		      "%s: particle %u's events (ev, own, ghost) are not those of the window's start",
		      after, i);
		LZ_REQUIRE(r->role[i] == q->role[i] && r->heard[i] == q->heard[i], "%s: particle %u: "
		      "role %d, heard %g; at the window's start %d, %g", after, i, r->role[i],
		      r->heard[i], q->role[i], q->heard[i]);
		LZ_REQUIRE(key == q->key[i], "%s: particle %u is keyed %.17g in the heap, it was %.17g "
		      "(save its key, and put it back with it)", after, i, key, q->key[i]);
		LZ_REQUIRE(r->role[i] == LZ_PEDMD_ABSENT || in_cell(e, i, e->p[i].cell), "%s: particle %u "
		      "is not in the list of its cell %u (put it back where it was)", after, i,
		      e->p[i].cell);
	}
	LZ_REQUIRE(r->clock == q->clock && e->now == q->now, "%s: the clock reads %.17g (now %.17g), "
	      "it read %.17g (%.17g) at the window's start", after, r->clock, e->now, q->clock, q->now);
	LZ_REQUIRE(e->events == q->events && e->collisions == q->collisions &&
	      e->crossings == q->crossings, "%s: the system's counters read %llu events, %llu "
	      "collisions; at the window's start %llu, %llu (*r->e = r->snap)", after,
	      (unsigned long long)e->events, (unsigned long long)e->collisions,
	      (unsigned long long)q->events, (unsigned long long)q->collisions);
	LZ_REQUIRE(lz_heap_audit(e->heap) == LZ_OK, "%s: the heap is broken: %s", after,
	      lz_error_message());
}

LZ_TEST(save_and_restore_undo_a_window)
{
	lz_edmd *s = gas(2, 200, 0.35, LZ_EDMD_WALLS_NONE, 0, 1, 602);
	team q = team_new(s, 1, LZ_PEDMD_ROWS);
	lz_pedmd *r = q.r[0];
	lz_edmd *e = r->e;
	picture start = take_picture(r);

	/* changes by hand: a particle changed twice (only its first version counts), one
	 * moved to another cell, one out of the heap, the scalars and the clock */
	ck_assert_int_eq(lz_pedmd_save(r, 3), LZ_OK);
	e->p[3].v[0] += 1;
	e->p[3].count += 5;
	r->own[3].t = 99;
	r->heard[3] = 0.25;
	lz_heap_update(e->heap, 3, 7.5);
	ck_assert_int_eq(lz_pedmd_save(r, 3), LZ_OK);
	e->p[3].r[1] += 0.125;
	r->ghost[3].t = 42;
	lz_heap_update(e->heap, 3, 0.5);
	uint32_t far = (e->p[5].cell + (uint32_t)e->ncells / 2) % (uint32_t)e->ncells;
	ck_assert_int_eq(lz_pedmd_save(r, 5), LZ_OK);
	lz_edmd_cell_remove(e, 5);
	lz_edmd_cell_insert(e, 5, far);
	uint32_t top = lz_heap_top(e->heap);
	ck_assert_int_eq(lz_pedmd_save(r, top), LZ_OK);
	lz_heap_pop(e->heap);
	lz_edmd_cell_remove(e, top);  /* gone from this rank: in no cell */
	r->role[top] = LZ_PEDMD_ABSENT;
	uint32_t c7 = e->p[7].cell;
	double read7 = r->read[c7];
	lz_pedmd_read_at(r, c7, 1.25);  /* a prediction read cell c7 */
	lz_pedmd_read_at(r, c7, 1.375);
	e->now = r->clock = 1.5;
	e->events += 1000;
	e->collisions += 400;
	lz_pedmd_restore(r);
	check_picture(r, &start, "a record changed twice, one moved, one out of the heap, then restore");
	LZ_REQUIRE(r->read[c7] == read7, "cell %u was read at 1.25 and 1.375 in the window; after the "
	      "restore its stamp reads %g, at the window's start %g (lz_pedmd_unread)", c7,
	      r->read[c7], read7);

	/* 400 events of the rank's own, restored; run again, the same events (a collision
	 * sits in the heap twice, under both particles: either may come first) */
	double t1[400];
	uint32_t i1[400], j1[400];
	for (int pass = 0; pass < 2; pass++) {
		ck_assert_int_eq(lz_pedmd_begin(r, INFINITY), LZ_OK);
		for (int k = 0; k < 400; k++) {
			uint32_t i = lz_heap_top(e->heap);
			double t = lz_heap_top_t(e->heap);
			uint32_t j = e->ev[i].partner >= 0 ? (uint32_t)e->ev[i].partner : i;
			int did = 0;
			LZ_REQUIRE(lz_pedmd_step(r, &did) == LZ_OK && did, "event %d: %s", k, lz_error_message());
			if (pass == 0) {
				t1[k] = t;
				i1[k] = i;
				j1[k] = j;
			}
			LZ_REQUIRE(t == t1[k] && ((i == i1[k] && j == j1[k]) || (i == j1[k] && j == i1[k])),
			      "event %d after a restore is particle %u (with %u) at %.17g; before it was %u "
			      "(with %u) at %.17g: the restored state is not the start's", k, i, j, t, i1[k],
			      j1[k], t1[k]);
		}
		lz_pedmd_restore(r);
		check_picture(r, &start, "400 events, then restore");
	}
	free_picture(&start);
	team_free(&q);
	lz_edmd_free(s);
}
END_TEST

/* ---- step ---- */

/* What a serial event is, seen before lz_edmd_step carries it out. */
static lz_pedmd_record serial_event(const lz_edmd *e)
{
	uint32_t i = lz_heap_top(e->heap);
	lz_edmd_event ev = e->ev[i];
	lz_pedmd_record q = {e->t_base + lz_heap_top_t(e->heap), i, i, LZ_PEDMD_CROSSING, 0};
	if (ev.partner >= 0 && e->p[ev.partner].count == ev.pcount) {
		q.kind = LZ_PEDMD_COLLISION;
		q.i = i < (uint32_t)ev.partner ? i : (uint32_t)ev.partner;
		q.j = i < (uint32_t)ev.partner ? (uint32_t)ev.partner : i;
	} else if (ev.partner >= 0) {
		q.kind = LZ_PEDMD_STALE;
	}
	return q;
}

/* A serial run to t_stop, re-based at the multiples of tau as the ranks do, its
 * events into log (when not NULL, room for cap). The number of events. */
static size_t serial_run(lz_edmd *e, double t_stop, double tau, lz_pedmd_record *log, size_t cap)
{
	size_t n = 0;
	for (double T = (floor(lz_edmd_time(e) / tau) + 1) * tau;; T += tau) {
		double stop = fmin(T, t_stop);
		while (e->t_base + lz_heap_top_t(e->heap) <= stop) {
			lz_pedmd_record q = serial_event(e);
			uint64_t bounces = e->bounces;
			LZ_REQUIRE(lz_edmd_step(e) >= 0, "the serial run stopped: nothing left to happen");
			if (q.kind == LZ_PEDMD_CROSSING && e->bounces > bounces)
				q.kind = LZ_PEDMD_BOUNCE;
			if (log) {
				LZ_REQUIRE(n < cap, "more than %zu serial events", cap);
				log[n] = q;
			}
			n++;
		}
		e->now = stop - e->t_base;
		lz_edmd_sync(e);
		if (stop >= t_stop)
			return n;
		lz_edmd_rebase(e);
	}
}

/* One rank alone steps as the serial engine: the same event, the same bits. */
static void check_alone(int dim, size_t n, double eta, int walls, double g, double rest,
                        const char *what)
{
	lz_edmd *a = gas(dim, n, eta, walls, g, rest, 603);
	lz_edmd *s = gas(dim, n, eta, walls, g, rest, 603);
	team q = team_new(s, 1, LZ_PEDMD_MORTON);
	lz_pedmd *r = q.r[0];
	lz_edmd *e = r->e;
	for (int k = 0; k < 4000; k++) {
		lz_pedmd_record want = serial_event(a);
		uint64_t bounces = a->bounces;
		uint32_t i = lz_heap_top(e->heap);
		double t = lz_heap_top_t(e->heap);
		LZ_REQUIRE(i == lz_heap_top(a->heap) && t == lz_heap_top_t(a->heap), "%s, event %d: the "
		      "rank's next is particle %u at %.17g, the serial engine's %u at %.17g", what, k,
		      i, t, lz_heap_top(a->heap), lz_heap_top_t(a->heap));
		int did = 0;
		LZ_REQUIRE(lz_pedmd_step(r, &did) == LZ_OK && did == 1, "%s, event %d: lz_pedmd_step "
		      "returned with did = %d: %s", what, k, did, lz_error_message());
		lz_edmd_step(a);
		if (want.kind == LZ_PEDMD_CROSSING && a->bounces > bounces)
			want.kind = LZ_PEDMD_BOUNCE;
		LZ_REQUIRE(r->clock == t && e->now == t, "%s, event %d at %.17g: the rank's clock reads "
		      "%.17g and now %.17g — both move to the event's time", what, k, t, r->clock, e->now);
		LZ_REQUIRE(r->nwlog == (size_t)k + 1, "%s, event %d: the window's log holds %zu events "
		      "(lz_pedmd_note, once per event)", what, k, r->nwlog);
		const lz_pedmd_record *got = &r->wlog[k];
		LZ_REQUIRE(got->t == want.t && got->i == want.i && got->j == want.j &&
		      got->kind == want.kind, "%s, event %d: noted as kind %u of (%u, %u) at %.17g, the serial "
		      "event is kind %u of (%u, %u) at %.17g (0 collision, 1 crossing, 2 bounce, 3 "
		      "stale)", what, k, got->kind, got->i, got->j, got->t, want.kind, want.i, want.j,
		      want.t);
		uint32_t j = want.j;
		LZ_REQUIRE(same_particle(&e->p[i], &a->p[i]) && same_particle(&e->p[j], &a->p[j]),
		      "%s, event %d (kind %u, particles %u and %u): the records differ from the serial "
		      "engine's — bring both to the event time, bounce, count, cross with the jump",
		      what, k, want.kind, want.i, want.j);
		LZ_REQUIRE(lz_heap_contains(e->heap, i) && lz_heap_key(e->heap, i) == lz_heap_key(a->heap, i),
		      "%s, event %d: particle %u's next event is at %.17g, the serial engine's at %.17g",
		      what, k, i, lz_heap_contains(e->heap, i) ? lz_heap_key(e->heap, i) : NAN,
		      lz_heap_key(a->heap, i));
	}
	LZ_REQUIRE(e->collisions == a->collisions && e->crossings == a->crossings &&
	      e->bounces == a->bounces && e->stale == a->stale && e->events == a->events,
	      "%s: the rank counted %llu collisions, %llu crossings, %llu bounces, %llu stale; "
	      "the serial engine %llu, %llu, %llu, %llu", what,
	      (unsigned long long)e->collisions, (unsigned long long)e->crossings,
	      (unsigned long long)e->bounces, (unsigned long long)e->stale,
	      (unsigned long long)a->collisions, (unsigned long long)a->crossings,
	      (unsigned long long)a->bounces, (unsigned long long)a->stale);
	LZ_REQUIRE(r->counts.processed == 4000, "%s: 4000 events processed, counted %llu", what,
	      (unsigned long long)r->counts.processed);
	for (uint32_t i = 0; i < n; i++)
		LZ_REQUIRE(same_particle(&e->p[i], &a->p[i]), "%s: after 4000 events particle %u differs "
		      "from the serial engine's", what, i);

	/* nothing is due before a window's end: no event */
	double next = lz_heap_top_t(e->heap);
	ck_assert_int_eq(lz_pedmd_begin(r, e->t_base + next * (1 - 1e-9) - 1e-12), LZ_OK);
	int did = 7;
	LZ_REQUIRE(lz_pedmd_step(r, &did) == LZ_OK && did == 0 && e->events == a->events,
	      "%s: the window ends just before the next event (at %.17g): lz_pedmd_step must do "
	      "nothing and say so (did = %d, %llu events)", what, next, did,
	      (unsigned long long)e->events);
	team_free(&q);
	lz_edmd_free(s);
	lz_edmd_free(a);
}

LZ_TEST(step_on_one_rank_is_the_serial_step)
{
	check_alone(2, 400, 0.45, LZ_EDMD_WALLS_NONE, 0, 1, "2D disks, η = 0.45, periodic");
	check_alone(3, 300, 0.25, LZ_EDMD_WALLS_BOX, 0.5, 1, "3D spheres in a box, gravity 0.5");
	check_alone(2, 300, 0.3, LZ_EDMD_WALLS_X, 1, 0.8, "2D, walls on x, gravity 1, restitution 0.8");
}
END_TEST

LZ_TEST(step_replicates_a_collision_across_the_border)
{
	/* particle 0 at y = 5 (rank 0's last row) moving up, particle 1 at y = 7 (rank 1's
	 * first row) moving down: they touch at t = 0.5, before either reaches y = 6 */
	double r[6] = {4.5, 5, 0, 4.7, 7, 0}, v[6] = {0, 1, 0, 0, -1, 0};
	duo d = duo_new(r, v);
	lz_edmd *a = d.a;
	lz_pedmd *r0 = d.q.r[0], *r1 = d.q.r[1];
	ck_assert_int_eq(lz_pedmd_role(r0, 0), LZ_PEDMD_OWNED);
	ck_assert_int_eq(lz_pedmd_role(r0, 1), LZ_PEDMD_GHOST);
	ck_assert_int_eq(lz_pedmd_role(r1, 1), LZ_PEDMD_OWNED);
	double t = lz_heap_top_t(a->heap);
	lz_edmd_step(a);  /* the serial collision */
	LZ_REQUIRE(a->collisions == 1 && t > 0.4 && t < 1, "the scene: the serial collision comes "
	      "at %g", t);

	int did = 0, count[3];
	lz_pedmd_message m;
	ck_assert_int_eq(lz_pedmd_step(r0, &did), LZ_OK);
	LZ_REQUIRE(did == 1 && r0->clock == t, "rank 0 owns particle 0, whose collision with the "
	      "ghost of 1 at t = %.17g is its next event: did = %d, clock %.17g", t, did, r0->clock);
	for (uint32_t i = 0; i < 2; i++)
		LZ_REQUIRE(same_particle(&r0->e->p[i], &a->p[i]), "rank 0 after the collision: particle "
		      "%u (%s) differs from the serial run's — a replicated collision bounces both, the "
		      "ghost too", i, i ? "the ghost" : "owned");
	LZ_REQUIRE(!lz_heap_contains(r0->e->heap, 1) && r0->ghost[1].t == INFINITY, "rank 0: the "
	      "ghost of 1 must not be predicted here (its owner does it and says so), and its old "
	      "event is void (ghost[1].t = %g, in the heap: %d)", r0->ghost[1].t,
	      lz_heap_contains(r0->e->heap, 1));
	LZ_REQUIRE(lz_heap_contains(r0->e->heap, 0) && r0->own[0].t == lz_heap_key(a->heap, 0),
	      "rank 0: particle 0 is predicted again at %.17g; the serial run says %.17g",
	      r0->own[0].t, lz_heap_key(a->heap, 0));
	LZ_REQUIRE(r0->nwlog == 1 && r0->wlog[0].kind == LZ_PEDMD_COLLISION && r0->wlog[0].i == 0 &&
	      r0->wlog[0].j == 1, "rank 0 owns the smaller number, 0: it notes the collision (0, 1), "
	      "once; its log holds %zu events", r0->nwlog);
	drain(r1, count, &m);
	LZ_REQUIRE(count[LZ_PEDMD_STATE] == 1 && count[LZ_PEDMD_MIGRATE] == 0 &&
	      count[LZ_PEDMD_LEAVE] == 0 && m.id == 0 && m.t == t && same_particle(&m.p, &a->p[0]),
	      "rank 1 holds particle 0's cell as HALO: it must hear of the collision once, a STATE "
	      "of particle 0 at %.17g with its new record; it got %d STATE, %d MIGRATE, %d LEAVE",
	      t, count[0], count[1], count[2]);

	ck_assert_int_eq(lz_pedmd_step(r1, &did), LZ_OK);
	LZ_REQUIRE(did == 1 && r1->clock == t, "rank 1: particle 1's next event is the same "
	      "collision with the ghost of 0: did = %d, clock %.17g", did, r1->clock);
	for (uint32_t i = 0; i < 2; i++)
		LZ_REQUIRE(same_particle(&r1->e->p[i], &a->p[i]), "rank 1 after the collision: particle "
		      "%u differs from the serial run's: both sides must compute the same bits", i);
	LZ_REQUIRE(r1->nwlog == 0 && r1->wcommit == 0, "rank 1 owns 1, the larger number: the "
	      "collision is committed by rank 0 only, yet rank 1 noted %zu events", r1->nwlog);
	ck_assert_int_eq(lz_pedmd_apply(r1, &m), LZ_OK);  /* the other half: nothing new */
	LZ_REQUIRE(same_particle(&r1->e->p[0], &a->p[0]) && r1->t_error == INFINITY, "rank 1, "
	      "after rank 0's news of the same collision: particle 0 changed or a causality error "
	      "(%g) was raised", r1->t_error);
	duo_free(&d);
}
END_TEST

LZ_TEST(step_hands_a_particle_over_at_the_border)
{
	/* particle 0 at y = 5.5 moving up crosses y = 6, into rank 1's slab, at t = 0.5;
	 * particle 1 far away in rank 0's interior row (y = 3) crosses x = 2 at t = 0.25 */
	double r[6] = {4.5, 5.5, 0, 2.25, 3, 0}, v[6] = {0, 1, 0, -1, 0, 0};
	duo d = duo_new(r, v);
	lz_edmd *a = d.a;
	lz_pedmd *r0 = d.q.r[0], *r1 = d.q.r[1];
	int did, count[3];
	lz_pedmd_message m;

	/* a crossing inside rank 0's interior: nobody hears of it */
	duo_step(&d, 0, &did);
	LZ_REQUIRE(did && same_particle(&r0->e->p[1], &a->p[1]) && in_cell(r0->e, 1, a->p[1].cell) &&
	      lz_pedmd_role(r0, 1) == LZ_PEDMD_OWNED, "rank 0: particle 1 crosses into cell %u of its "
	      "own interior at 0.25: it stays owned, in its new cell, with the serial record",
	      a->p[1].cell);
	drain(r1, count, &m);
	LZ_REQUIRE(count[0] + count[1] + count[2] == 0, "a crossing between two INTERIOR cells of "
	      "rank 0 concerns nobody else; rank 1 got %d messages", count[0] + count[1] + count[2]);

	/* the crossing into rank 1's slab: MIGRATE, and particle 0 stays as a ghost */
	duo_step(&d, 0, &did);
	LZ_REQUIRE(did && r0->clock == 0.5, "rank 0: particle 0 reaches y = 6 at 0.5: did = %d, clock "
	      "%.17g", did, r0->clock);
	LZ_REQUIRE(lz_pedmd_role(r0, 0) == LZ_PEDMD_GHOST && !lz_heap_contains(r0->e->heap, 0) &&
	      in_cell(r0->e, 0, a->p[0].cell) && same_particle(&r0->e->p[0], &a->p[0]),
	      "rank 0: particle 0 crossed into cell %u, which rank 1 owns: it leaves rank 0's heap and "
	      "stays as a ghost in that (HALO) cell with its record (role %d, in the heap: %d)",
	      a->p[0].cell, lz_pedmd_role(r0, 0), lz_heap_contains(r0->e->heap, 0));
	LZ_REQUIRE(r0->own[0].t == 0.5 && r0->ghost[0].t == INFINITY, "rank 0 remembers when "
	      "particle 0 left (own[0].t = %g, not 0.5), and knows no event of the ghost until its "
	      "new owner says (ghost[0].t = %g)", r0->own[0].t, r0->ghost[0].t);
	LZ_REQUIRE(r0->nwlog == 2 && r0->wlog[1].kind == LZ_PEDMD_CROSSING && r0->wlog[1].i == 0,
	      "rank 0 carried out the crossing: it notes it (its log holds %zu events)", r0->nwlog);
	drain(r1, count, &m);
	LZ_REQUIRE(count[LZ_PEDMD_MIGRATE] == 1 && count[LZ_PEDMD_STATE] == 0 && m.id == 0 &&
	      m.t == 0.5 && same_particle(&m.p, &a->p[0]), "rank 1, the new owner, gets one MIGRATE of "
	      "particle 0 at 0.5 with its record, and no STATE (it will announce the particle "
	      "itself); it got %d STATE, %d MIGRATE, %d LEAVE", count[0], count[1], count[2]);
	ck_assert_int_eq(lz_pedmd_step(r1, &did), LZ_OK);
	LZ_REQUIRE(did == 0, "rank 1 owns no particle yet: nothing to step");
	drain(r0, count, &m);
	LZ_REQUIRE(count[0] + count[1] + count[2] == 0, "rank 0 sent %d messages to itself: a rank "
	      "is never its own listener", count[0] + count[1] + count[2]);
	duo_free(&d);
}
END_TEST

/* ---- apply ---- */

/* A STATE of particle i with record p and no event, at time t. */
static lz_pedmd_message state_of(uint32_t i, const lz_edmd_particle *p, double t)
{
	lz_pedmd_message m = {t, i, LZ_PEDMD_STATE, *p, {INFINITY, {LZ_EDMD_NONE, 0}}};
	return m;
}

LZ_TEST(apply_moves_ghosts_and_finds_late_news)
{
	/* 0: rank 0's, at rest near the border (y = 5.5); 1: rank 1's, in its first row,
	 * a ghost on rank 0; 2: rank 1's, far inside (y = 9) */
	double r[9] = {5, 5.5, 0, 1, 7, 0, 9, 9, 0}, v[9] = {0, 0.0, 0, 0.5, 0, 0, 0, 0.25, 0};
	lz_edmd *s = slabs(3, r, v);
	team q = team_new(s, 2, LZ_PEDMD_ROWS);
	lz_pedmd *r0 = q.r[0];
	lz_edmd *e = r0->e;
	ck_assert_int_eq(lz_pedmd_role(r0, 1), LZ_PEDMD_GHOST);
	ck_assert_int_eq(lz_pedmd_role(r0, 2), LZ_PEDMD_ABSENT);
	r0->clock = e->now = 0.2;

	/* news from the future waits */
	lz_edmd_particle p = e->p[1];
	p.r[0] = 2.5;
	p.t0 = 0.3;
	lz_pedmd_message m = state_of(1, &p, 0.3);
	ck_assert_int_eq(lz_pedmd_apply(r0, &m), LZ_OK);
	LZ_REQUIRE(r0->nwait == 1 && e->p[1].r[0] == 1, "rank 0 at 0.2 gets news of 0.3: it waits "
	      "(queued: %zu) and changes nothing yet (x = %g)", r0->nwait, e->p[1].r[0]);

	/* news of the past that nobody used: the ghost moves to its new cell */
	uint32_t c0 = e->p[1].cell;
	p = e->p[1];
	p.r[0] = 2.1;
	p.t0 = 0.1;
	p.cell = c0 + 1;  /* x = 2.1: the next column */
	m = state_of(1, &p, 0.1);
	m.event = (lz_pedmd_event){0.9, {0, e->p[0].count}};  /* aimed at owned 0 */
	ck_assert_int_eq(lz_pedmd_apply(r0, &m), LZ_OK);
	LZ_REQUIRE(same_particle(&e->p[1], &p) && in_cell(e, 1, c0 + 1) && !in_cell(e, 1, c0) &&
	      r0->t_error == INFINITY, "a STATE of 0.1 for the ghost of 1, applied at 0.2 with nothing "
	      "read since: its record and cell become the message's (in cell %u: %d, still in %u: %d; "
	      "causality error at %g)", c0 + 1, in_cell(e, 1, c0 + 1), c0, in_cell(e, 1, c0),
	      r0->t_error);
	LZ_REQUIRE(memcmp(&r0->ghost[1], &m.event, sizeof m.event) == 0 && r0->heard[1] == 0.1,
	      "the ghost's event and the time of the news are kept (ghost[1].t = %g, heard %g)",
	      r0->ghost[1].t, r0->heard[1]);
	LZ_REQUIRE(lz_heap_key(e->heap, 0) == 0.9 && e->ev[0].partner == 1, "the ghost of 1 now aims "
	      "at owned particle 0 at 0.9, earlier than 0's own event (%g): 0 is keyed %.17g with "
	      "partner %d — the owned particles a ghost aims at get their keys again",
	      r0->own[0].t, lz_heap_key(e->heap, 0), e->ev[0].partner);

	/* older news than the ghost has: ignored */
	lz_edmd_particle was = e->p[1];
	p.r[0] = 3.3;
	m = state_of(1, &p, 0.05);
	ck_assert_int_eq(lz_pedmd_apply(r0, &m), LZ_OK);
	LZ_REQUIRE(same_particle(&e->p[1], &was), "a STATE of 0.05 after one of 0.1: the older news "
	      "(a former owner's) must not undo the newer");

	/* its aim moves away: 0 goes back to its own event */
	p = e->p[1];
	m = state_of(1, &p, 0.15);
	ck_assert_int_eq(lz_pedmd_apply(r0, &m), LZ_OK);
	LZ_REQUIRE(lz_heap_key(e->heap, 0) == r0->own[0].t, "the ghost of 1 no longer aims at 0: 0's "
	      "key is its own event again (%.17g), not %.17g", r0->own[0].t, lz_heap_key(e->heap, 0));

	/* a prediction at 0.18 read the ghost's cell: news of 0.16 is a causality error */
	r0->read[e->p[1].cell] = 0.18;
	p.r[0] = 2.2;
	m = state_of(1, &p, 0.16);
	ck_assert_int_eq(lz_pedmd_apply(r0, &m), LZ_OK);
	LZ_REQUIRE(r0->t_error == 0.16, "rank 0 read cell %u at 0.18; a STATE of 0.16 for a ghost "
	      "there arrives late: a causality error at 0.16, found %g", e->p[1].cell, r0->t_error);

	/* LEAVE: the ghost is gone */
	r0->t_error = INFINITY;
	r0->read[e->p[1].cell] = -INFINITY;
	uint32_t c1 = e->p[1].cell;
	m = state_of(1, &e->p[1], 0.17);
	m.kind = LZ_PEDMD_LEAVE;
	ck_assert_int_eq(lz_pedmd_apply(r0, &m), LZ_OK);
	LZ_REQUIRE(lz_pedmd_role(r0, 1) == LZ_PEDMD_ABSENT && !in_cell(e, 1, c1) &&
	      r0->t_error == INFINITY, "a LEAVE of the ghost of 1: it is ABSENT and out of cell %u "
	      "(role %d, still in the cell: %d)", c1, lz_pedmd_role(r0, 1), in_cell(e, 1, c1));

	/* a message of no known kind is an error, not a crash */
	m.kind = 17;
	LZ_REQUIRE(lz_pedmd_apply(r0, &m) != LZ_OK, "a message of kind 17 must be refused");
	team_free(&q);
	lz_edmd_free(s);
}
END_TEST

LZ_TEST(apply_takes_over_a_migrated_particle)
{
	/* as in the hand-over: particle 0 crosses into rank 1's slab at 0.5; particle 1 sits
	 * in rank 1's first row, at rest */
	double r[6] = {4.5, 5.5, 0, 7.5, 7, 0}, v[6] = {0, 1, 0, 0, 0, 0};
	duo d = duo_new(r, v);
	lz_edmd *a = d.a;
	lz_pedmd *r0 = d.q.r[0], *r1 = d.q.r[1];
	int did, count[3];
	lz_pedmd_message m;
	duo_step(&d, 0, &did);
	drain(r1, count, &m);
	LZ_REQUIRE(count[LZ_PEDMD_MIGRATE] == 1, "the scene: rank 1 gets a MIGRATE (%d)", count[1]);

	/* a copy of rank 1 whose particle 1 moved on past 0.5: the block is not at 0.5 */
	lz_edmd *e1 = r1->e;
	lz_edmd_particle keep = e1->p[1];
	e1->p[1].t0 = 0.75;
	r1->clock = e1->now = 0.8;
	ck_assert_int_eq(lz_pedmd_apply(r1, &m), LZ_OK);
	LZ_REQUIRE(r1->t_error == 0.5 && lz_pedmd_role(r1, 0) != LZ_PEDMD_OWNED, "rank 1 is at 0.8 and "
	      "particle 1 of the new cell's block is at its own time 0.75: particle 0 handed over at "
	      "0.5 cannot be predicted at 0.5 any more — a causality error at 0.5 (found %g, role %d)",
	      r1->t_error, lz_pedmd_role(r1, 0));

	/* in time: rank 1 at 0.6 takes particle 0 over and predicts it at 0.5 */
	e1->p[1] = keep;
	r1->t_error = INFINITY;
	r1->clock = e1->now = 0.6;
	ck_assert_int_eq(lz_pedmd_apply(r1, &m), LZ_OK);
	LZ_REQUIRE(lz_pedmd_role(r1, 0) == LZ_PEDMD_OWNED && lz_heap_contains(e1->heap, 0) &&
	      in_cell(e1, 0, a->p[0].cell) && same_particle(&e1->p[0], &a->p[0]), "rank 1 at 0.6 takes "
	      "particle 0 over: OWNED, in its heap and in cell %u with the record sent (role %d)",
	      a->p[0].cell, lz_pedmd_role(r1, 0));
	LZ_REQUIRE(lz_heap_key(e1->heap, 0) == lz_heap_key(a->heap, 0) &&
	      e1->ev[0].partner == a->ev[0].partner, "rank 1 predicts particle 0 at the crossing, 0.5, "
	      "as the serial run does: next event at %.17g (partner %d), the serial %.17g (%d)",
	      lz_heap_key(e1->heap, 0), e1->ev[0].partner, lz_heap_key(a->heap, 0), a->ev[0].partner);
	LZ_REQUIRE(r1->t_error == INFINITY && e1->now == 0.6, "taking over in time is no causality "
	      "error (%g), and the rank's time is left where it was (now = %.17g)", r1->t_error,
	      e1->now);
	drain(r0, count, &m);
	LZ_REQUIRE(count[LZ_PEDMD_STATE] == 1 && m.id == 0, "rank 0 holds the new cell as HALO: the "
	      "new owner announces particle 0 with its prediction (%d STATE)", count[0]);

	/* rank 0 handed 0 over at 0.5; late news of 1 whose next event hits 0 */
	lz_pedmd_message n = state_of(1, &r0->e->p[1], 0.1);
	n.event = (lz_pedmd_event){0.7, {0, r0->e->p[0].count}};
	ck_assert_int_eq(lz_pedmd_apply(r0, &n), LZ_OK);
	LZ_REQUIRE(r0->t_error == INFINITY, "rank 0 gets news of 0.1: the ghost of 1 will hit "
	      "particle 0 at 0.7, after 0 went over to rank 1 at 0.5 — rank 1's collision, no "
	      "causality error here (found %g)", r0->t_error);
	n.event.t = 0.4;
	ck_assert_int_eq(lz_pedmd_apply(r0, &n), LZ_OK);
	LZ_REQUIRE(r0->t_error >= 0.1 && r0->t_error <= 0.4, "rank 0 gets news of 0.1: the ghost "
	      "of 1 hits particle 0 at 0.4, when rank 0 still owned 0 (it handed it over at 0.5, "
	      "crossing instead of colliding): a causality error at 0.4 (or earlier, down to the "
	      "news), found %g — the rank must remember when a particle left", r0->t_error);
	duo_free(&d);
}
END_TEST

/* ---- decide ---- */

LZ_TEST(decide_commits_rolls_back_or_steps)
{
	double end = -1;
	LZ_REQUIRE(lz_pedmd_decide(INFINITY, 2.0, 2.5, &end) == LZ_PEDMD_COMMIT, "no causality "
	      "error anywhere: the window commits");
	double Ts[] = {0, 2.0, 1e12};
	for (int k = 0; k < 3; k++) {
		double T = Ts[k], err = T + 0.25 + T * 1e-10;
		int v = lz_pedmd_decide(err, T, T + 0.1, &end);
		LZ_REQUIRE(v == LZ_PEDMD_ROLLBACK && end == err, "window from %.17g, an error at %.17g: "
		      "roll back, and end the next window at the error (its events run; ending before it "
		      "leaves the late message to start the window after, which can then only take a "
		      "conservative step): got verdict %d, end %.17g", T, err, v, end);
		v = lz_pedmd_decide(T, T, T + 0.1, &end);
		LZ_REQUIRE(v == LZ_PEDMD_CONSERVATIVE && end == T + 0.1, "an error at the window's very "
		      "start %.17g: no window can end before it — a conservative step to the earliest "
		      "event, %.17g; got verdict %d, end %.17g", T, T + 0.1, v, end);
		double just = nextafter(T, INFINITY);
		v = lz_pedmd_decide(just, T, T + 0.1, &end);
		LZ_REQUIRE(v == LZ_PEDMD_ROLLBACK && end == just, "an error one double after the "
		      "window's start %.17g: a window of one double is still a window — roll back to it "
		      "(verdict %d, end %.17g)", T, v, end);
	}
}
END_TEST

/* ---- rebalance ---- */

/* The largest rank load of cuts `cut`: each cell's load to the rank whose run of the
 * curve holds its place. */
static double largest_load(const lz_pedmd_domains *d, const double *load, const uint32_t *cut)
{
	double sum[LZ_PEDMD_RANKS_MAX] = {0}, most = 0;
	for (uint32_t c = 0; c < d->ncells; c++) {
		int r = 0;
		while (d->place[c] >= cut[r + 1])
			r++;
		sum[r] += load[c];
		most = fmax(most, sum[r]);
	}
	return most;
}

/* The least largest load over every placement of the cuts (small grids only). */
static double best_load(const lz_pedmd_domains *d, const double *load, uint32_t *cut, int r)
{
	int P = d->P;
	if (r == P)
		return largest_load(d, load, cut);
	double best = INFINITY;
	for (uint32_t c = cut[r - 1] + 1; c + (uint32_t)(P - r) <= d->ncells; c++) {
		cut[r] = c;
		best = fmin(best, best_load(d, load, cut, r + 1));
	}
	return best;
}

/* lz_pedmd_rebalance on load, checked; its verdict. */
static int check_rebalance(const lz_pedmd_domains *d, const double *load, double threshold,
                           const char *what)
{
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1], opt[LZ_PEDMD_RANKS_MAX + 1];
	int P = d->P, moved = lz_pedmd_rebalance(d, load, threshold, cut);
	double old = largest_load(d, load, d->cut), most = 0, total = 0;
	for (size_t c = 0; c < d->ncells; c++) {
		total += load[c];
		most = fmax(most, load[c]);
	}
	LZ_REQUIRE(cut[0] == 0 && cut[P] == d->ncells, "%s: the cuts run from %u to %u, not 0 to %zu",
	      what, cut[0], cut[P], d->ncells);
	for (int r = 0; r < P; r++)
		LZ_REQUIRE(cut[r] < cut[r + 1], "%s: rank %d gets cells %u .. %u of the curve: every rank "
		      "keeps at least one cell", what, r, cut[r], cut[r + 1]);
	double now = largest_load(d, load, cut);
	if (!moved) {
		LZ_REQUIRE(memcmp(cut, d->cut, (size_t)(P + 1) * sizeof *cut) == 0, "%s: no move, so "
		      "new_cut must be the old cuts", what);
		return 0;
	}
	LZ_REQUIRE(now <= (1 - threshold) * old, "%s: the new cuts were taken with a largest load of "
	      "%g against %g before: not %g%% better", what, now, old, 100 * threshold);
	LZ_REQUIRE(now <= total / P + most + 1e-9 * total, "%s: with cuts where the running load "
	      "passes k/P of the total %g, no rank carries more than %g + the largest cell, %g; the "
	      "largest carries %g", what, total, total / P, most, now);
	if (d->ncells <= 16) {
		opt[0] = 0;
		opt[P] = (uint32_t)d->ncells;
		double best = best_load(d, load, opt, 1);
		LZ_REQUIRE(now <= best + most, "%s: the best cuts give a largest load of %g; these %g",
		      what, best, now);
	}
	return 1;
}

LZ_TEST(rebalance_evens_the_load)
{
	gsl_rng *g = lz_test_rng(604);
	uint32_t even[] = {0, 4, 8, 12, 16};
	lz_pedmd_domains *d = hand_domains(16, 4, even, g);
	double load[64];

	for (int c = 0; c < 16; c++)
		load[c] = 10;
	LZ_REQUIRE(check_rebalance(d, load, 0.1, "an even load") == 0, "an even load: the cuts stay");

	memset(load, 0, sizeof load);
	for (uint32_t k = 0; k < 4; k++)
		load[d->curve[k]] = 25;  /* everything in rank 0's cells, along the curve */
	LZ_REQUIRE(check_rebalance(d, load, 0.1, "all the load on rank 0") == 1, "all the load on "
	      "rank 0's four cells: the cuts must move (one loaded cell each)");

	memset(load, 0, sizeof load);
	for (uint32_t k = 13; k < 16; k++)
		load[d->curve[k]] = 30;  /* everything at the end of the curve */
	load[d->curve[0]] = 1;
	LZ_REQUIRE(check_rebalance(d, load, 0.1, "the load at the curve's end") == 1, "the load in "
	      "the last three cells of the curve: the cuts must move there");

	memset(load, 0, sizeof load);
	load[d->curve[5]] = load[d->curve[6]] = 100;  /* two hot cells of rank 1 */
	LZ_REQUIRE(check_rebalance(d, load, 0.1, "two hot cells in the middle") == 1, "all the load "
	      "in two neighbouring cells of rank 1: the cuts must move to split them");

	for (int c = 0; c < 16; c++)
		load[c] = 10 + (d->place[c] < 4 ? 1 : 0);  /* rank 0 carries 10 % more */
	LZ_REQUIRE(check_rebalance(d, load, 0.1, "10 % more on rank 0") == 0, "rank 0 carries 44 "
	      "against 40: no cut can make that 10 %% better, so the cuts stay");

	memset(load, 0, sizeof load);
	LZ_REQUIRE(check_rebalance(d, load, 0.1, "no load") == 0, "no load at all: the cuts stay");
	lz_pedmd_domains_free(d);

	uint32_t cuts5[] = {0, 12, 25, 38, 51, 64};
	d = hand_domains(64, 5, cuts5, g);
	for (int trial = 0; trial < 50; trial++) {
		for (int c = 0; c < 64; c++)
			load[c] = gsl_rng_uniform(g) < 0.3 ? 100 * gsl_rng_uniform(g) : 0;
		check_rebalance(d, load, 0.05, "random loads over 64 cells, five ranks");
	}
	lz_pedmd_domains_free(d);
	gsl_rng_free(g);
}
END_TEST

/* ---- whole runs ---- */

typedef struct {
	int dim;
	size_t n;
	double eta;
	int walls;
	double g, restitution, t0, t;
	int P, kind;
	lz_stub_policy policy;
} scene;

/* The parallel run of sc against the serial run: records, counts and logs equal. */
static lz_pedmd_counts check_run(const scene *sc, const char *what)
{
	lz_edmd *a = gas(sc->dim, sc->n, sc->eta, sc->walls, sc->g, sc->restitution, 605);
	lz_edmd *s = gas(sc->dim, sc->n, sc->eta, sc->walls, sc->g, sc->restitution, 605);
	if (sc->t0 != 0) {
		lz_edmd_set_time(a, sc->t0);
		lz_edmd_set_time(s, sc->t0);
	}
	size_t cap = 200000;
	lz_pedmd_record *want = malloc(cap * sizeof *want);
	LZ_REQUIRE(want, "out of memory");
	double t_stop = sc->t0 + sc->t;
	size_t nwant = serial_run(a, t_stop, PARAMS.rebase, want, cap);
	qsort(want, nwant, sizeof *want, lz_pedmd_record_order);  /* ties at a large clock */
	lz_stub_params sp = {sc->P, sc->policy, 606, 3, 0, 4, 1e-6, 2e-6, 5e-6};
	lz_pedmd_params pp = PARAMS;
	pp.compact = 1;  /* local numbering, as lz-mpi runs: a slot is not a particle's number */
	lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, sc->kind, &sp, &pp);
	LZ_REQUIRE(x, "%s: %s", what, lz_error_message());
	x->audit = 1;
	x->most = 40 * nwant + 10000;  /* the runs here process 1-5 events per committed one */
	int st = lz_pedmd_sim_run(x, t_stop);
	LZ_REQUIRE(st == LZ_OK, "%s: the run failed: %s", what, lz_error_message());
	lz_pedmd_counts c = lz_pedmd_sim_counts(x);
	LZ_REQUIRE(c.committed == nwant, "%s: %llu events committed, the serial run has %zu (%llu "
	      "rollbacks, %llu conservative steps)", what, (unsigned long long)c.committed, nwant,
	      (unsigned long long)c.rollbacks, (unsigned long long)c.conservative);
	size_t ngot;
	lz_pedmd_record *got = lz_pedmd_sim_log(x, &ngot);
	LZ_REQUIRE(ngot == nwant, "%s: the ranks' logs hold %zu events, the serial run %zu", what,
	      ngot, nwant);
	for (size_t k = 0; k < ngot; k++)
		LZ_REQUIRE(got[k].t == want[k].t && got[k].i == want[k].i && got[k].j == want[k].j &&
		      got[k].kind == want[k].kind, "%s: committed event %zu is kind %u of (%u, %u) at %.17g; "
		      "the serial run's is kind %u of (%u, %u) at %.17g", what, k, got[k].kind, got[k].i,
		      got[k].j, got[k].t, want[k].kind, want[k].i, want[k].j, want[k].t);
	lz_pedmd_sim_gather(x, s);
	for (uint32_t i = 0; i < sc->n; i++)
		LZ_REQUIRE(memcmp(s->p[i].r, a->p[i].r, sizeof a->p[i].r) == 0 &&
		      memcmp(s->p[i].v, a->p[i].v, sizeof a->p[i].v) == 0 && s->p[i].t0 == a->p[i].t0,
		      "%s: at the end particle %u is at (%.17g, %.17g) with v = (%.17g, %.17g); in the "
		      "serial run at (%.17g, %.17g), (%.17g, %.17g)", what, i, s->p[i].r[0], s->p[i].r[1],
		      s->p[i].v[0], s->p[i].v[1], a->p[i].r[0], a->p[i].r[1], a->p[i].v[0], a->p[i].v[1]);
	LZ_REQUIRE(x->audits > 2, "%s: only %llu cuts audited", what, (unsigned long long)x->audits);
	free(got);
	free(want);
	lz_pedmd_sim_free(x);
	lz_edmd_free(s);
	lz_edmd_free(a);
	return c;
}

LZ_TEST(parallel_run_commits_the_serial_events)
{
	uint64_t rollbacks = 0, conservative = 0;
	char what[160];
	for (int P = 2; P <= 4; P++)
		for (int kind = 0; kind < 2; kind++)
			for (int policy = 0; policy < 2; policy++) {
				scene sc = {2, 400, 0.3, LZ_EDMD_WALLS_NONE, 0, 1, 0, 1.5, P, kind, policy};
				snprintf(what, sizeof what, "2D disks, N = 400, η = 0.3, P = %d, %s, %s", P,
				         kind ? "Morton" : "rows", policy ? "random order" : "round robin");
				lz_pedmd_counts c = check_run(&sc, what);
				rollbacks += c.rollbacks;
				conservative += c.conservative;
			}
	LZ_REQUIRE(rollbacks > 0 && conservative == 0, "the runs had %llu rollbacks and %llu "
	      "conservative steps: late messages must have happened, and a rollback that ends the "
	      "next window at the error never needs a conservative step (the error cannot come "
	      "again at a window's end)", (unsigned long long)rollbacks,
	      (unsigned long long)conservative);
}
END_TEST

LZ_TEST(parallel_run_with_walls_gravity_and_loss)
{
	scene sc[] = {
		{3, 500, 0.2, LZ_EDMD_WALLS_BOX, 1, 0.9, 0, 0.6, 4, LZ_PEDMD_MORTON, LZ_STUB_RANDOM},
		{3, 1500, 0.3, LZ_EDMD_WALLS_NONE, 0, 1, 0, 0.25, 8, LZ_PEDMD_MORTON, LZ_STUB_VIRTUAL},
		{2, 400, 0.3, LZ_EDMD_WALLS_X, 1, 0.8, 0, 1, 3, LZ_PEDMD_ROWS, LZ_STUB_AHEAD},
	};
	const char *what[] = {"3D box, gravity 1, restitution 0.9, P = 4 Morton",
	                      "3D periodic, N = 1500, P = 8 Morton, virtual time",
	                      "2D walls on x, gravity 1, restitution 0.8, P = 3 rows, one rank ahead"};
	for (int k = 0; k < 3; k++)
		check_run(&sc[k], what[k]);
}
END_TEST

LZ_TEST(parallel_run_at_the_extremes)
{
	scene sc[] = {
		{2, 1, 0.01, LZ_EDMD_WALLS_NONE, 0, 1, 0, 3, 2, LZ_PEDMD_ROWS, LZ_STUB_RANDOM},
		{2, 2, 0.05, LZ_EDMD_WALLS_NONE, 0, 1, 0, 5, 2, LZ_PEDMD_ROWS, LZ_STUB_RANDOM},
		{2, 400, 0.3, LZ_EDMD_WALLS_NONE, 0, 1, 1e12, 1, 3, LZ_PEDMD_ROWS, LZ_STUB_RANDOM},
		{2, 900, 0.65, LZ_EDMD_WALLS_NONE, 0, 1, 0, 0.3, 4, LZ_PEDMD_MORTON, LZ_STUB_VIRTUAL},
		{3, 400, 0.02, LZ_EDMD_WALLS_NONE, 0, 1, 0, 4, 4, LZ_PEDMD_MORTON, LZ_STUB_RANDOM},
	};
	const char *what[] = {"one particle, two ranks", "two particles, two ranks",
	                      "the clock at 10^12", "dense disks, η = 0.65", "a dilute gas, η = 0.02"};
	for (int k = 0; k < 5; k++)
		check_run(&sc[k], what[k]);
}
END_TEST
