/* lz_mpi.c — the program lz-mpi: a `method = pedmd` scene with one process per rank.
 *
 *   mpirun -np P lz-mpi SCENE [key=value ...]
 *
 * Every process reads the scene, applies the overrides and binds the pedmd keys; the
 * seed that rank 0 drew for seed = auto is everyone's. Rank 0 alone builds and
 * equilibrates the system (lz_pedmd_scene_make) and sends its box and clock to the
 * others. The P processes are the ranks (a scene's `ranks` must agree, or be left
 * out); each opens empty in local numbering (lz_pedmd_open) and takes its share — the
 * particles of its cells and halo — from rank 0, in rounds (spread: each particle to
 * the ranks that hold its cell); then rank 0 frees the start, so that no process
 * holds all N during the run (on one process the rank takes the start itself,
 * lz_pedmd_adopt). Each runs its domain over the MPI back-end (lz/msg_mpi.h) until
 * t_stop. Then rank 0 gathers the owned particles into a frame of all N
 * (lz_pedmd_release), in rounds, sums the counters, prints a short report (stdout:
 * with the memory of rank 0 and of the largest other process, in the run and at the
 * peak) and, with check = yes, runs the serial reference and compares bit for bit.
 * Before the run, ranks 0 and 1 measure what a message costs and how long it travels
 * (probe): the report prints both, for the virtual-time model of `make bench`.
 * The stub's keys (schedule, delay, costs, latency) and write_config mean nothing here.
 * balance = pilot: rank 0 runs a pilot in one process first (over the stub: its
 * committed events per cell do not depend on the schedule) and every rank takes its
 * cuts. balance = dynamic: at every cut that lz_pedmd_balance_due names, the
 * ranks sum their load since the last look (MPI_Allreduce), all find the same new
 * cuts, and when these pay every particle goes from its owner to the ranks that now
 * hold its cell (its new owner and those with the cell as halo), in rounds, never the
 * whole picture at once (lz_pedmd_take_begin .. _end), as at the start.
 *
 * Exit status, the same on every process: 0 success; 1 the run failed or differs from
 * the serial run; 2 bad input (usage, scene file, key, value, ranks). A failure while
 * the processes are set up is agreed on collectively (an MPI_Allreduce of the status:
 * the first failing rank says why, every process exits); one inside the run, where the
 * others would wait for it forever, prints its message and calls MPI_Abort.
 */
#include <math.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include <mpi.h>

#include "lz/edmd.h"
#include "lz/error.h"
#include "lz/msg_mpi.h"
#include "lz/pedmd.h"
#include "method.h"
#include "pedmd_scene.h"
#include "scene.h"

enum { USAGE = -1 };  /* a usage error: the message, then the usage line */

/* The code of the last lz_error: lz_scene_read reports failure with NULL. The
 * messages are printed once, by the rank that speaks for all (lz_error_message). */
static int last_code;
static void record(int code, const char *message) { last_code = code; }

static int exit_status(int st)
{
	return st == LZ_OK ? 0 : st == USAGE || st == LZ_EINVAL || st == LZ_ESYNTAX ? 2 : 1;
}

/* Every process has status st: 1 when some rank failed — the first failing rank says
 * why, and every process gets its status in *agreed — else 0 (*agreed = LZ_OK).
 * Collective over MPI_COMM_WORLD. */
static int agree(int st, int rank, int size, int *agreed)
{
	int me = st != LZ_OK ? rank : size, first;
	MPI_Allreduce(&me, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
	*agreed = st;
	if (first == size)
		return 0;
	MPI_Bcast(agreed, 1, MPI_INT, first, MPI_COMM_WORLD);
	if (rank == first) {
		if (rank != 0)
			fprintf(stderr, "lz-mpi: rank %d: %s\n", rank, lz_error_message());
		else
			fprintf(stderr, "lz-mpi: %s\n", lz_error_message());
		if (st == USAGE)
			fputs("usage: mpirun -np P lz-mpi SCENE [key=value ...]\n", stderr);
	}
	return 1;
}

/* A failure inside the run: the others cannot be told, only stopped. (The engine's
 * messages mostly name the rank themselves.) */
static _Noreturn void abort_run(int rank, int st)
{
	const char *msg = lz_error_message();
	if (strncmp(msg, "rank ", 5) == 0)
		fprintf(stderr, "lz-mpi: %s\n", msg);
	else
		fprintf(stderr, "lz-mpi: rank %d: %s\n", rank, msg);
	MPI_Abort(MPI_COMM_WORLD, exit_status(st));
	exit(exit_status(st));  /* not reached */
}

/* The scene of argv, overridden, bound to the pedmd keys with `ranks` = size unless
 * it says otherwise. Local: every process does the same. */
static int load(int argc, char **argv, int size, lz_scene **sp)
{
	if (argc < 2)
		return lz_error(LZ_EINVAL, "lz-mpi needs a scene"), USAGE;
	lz_scene *s = *sp = lz_scene_read(argv[1]);
	if (!s)
		return last_code;
	int st;
	for (int i = 2; i < argc; i++) {
		if (!strchr(argv[i], '='))
			return lz_error(LZ_EINVAL, "unexpected argument '%s' (after SCENE come "
			                "key=value overrides)", argv[i]), USAGE;
		if ((st = lz_scene_set(s, argv[i], "command line")) != LZ_OK)
			return st;
	}
	const char *method = lz_scene_method(s);
	if (!method || strcmp(method, lz_method_pedmd.name) != 0)
		return lz_error(LZ_EINVAL, "%s: method = %s; lz-mpi runs the scenes of method "
		                "pedmd only", argv[1], method ? method : "(none)");
	char ranks[32];
	snprintf(ranks, sizeof ranks, "ranks=%d", size);
	if (!lz_scene_given(s, "ranks") && (st = lz_scene_set(s, ranks, "mpirun -np")) != LZ_OK)
		return st;
	return lz_method_bind(&lz_method_pedmd, s);
}

/* Rank 0's seeds for every process (seed = auto draws one per process), logged as
 * `lz run` does; the scene is bound again with them. */
static int share_seeds(lz_scene *s, int rank)
{
	const lz_key_table *t = &lz_method_pedmd.keys;
	int changed = 0;
	for (size_t i = 0; i < t->n; i++) {
		const char *key = t->key[i].name;
		if (t->key[i].type != LZ_KEY_SEED)
			continue;
		unsigned long seed = lz_scene_seed(s, key);
		if (rank == 0 && strcmp(lz_scene_text(s, key), "auto") == 0)
			fprintf(stderr, "lz-mpi: %s = %lu (auto); pass %s=%lu to repeat this run\n", key,
			        seed, key, seed);
		MPI_Bcast(&seed, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
		char set[128];
		snprintf(set, sizeof set, "%s=%lu", key, seed);
		int st = lz_scene_set(s, set, "rank 0");
		if (st != LZ_OK)
			return st;
		changed = 1;
	}
	return changed ? lz_method_bind(&lz_method_pedmd, s) : LZ_OK;
}

/* What only lz-mpi refuses, then the run: its system (and the reference, to check) on
 * rank 0 only — or on the one process —, the rest everywhere. */
static int make(lz_scene *s, int rank, int size, lz_pedmd_scene *p)
{
	if (lz_scene_given(s, "ranks") && lz_scene_int(s, "ranks") != size)
		return lz_scene_fail(s, "ranks", "ranks = %lld, but lz-mpi runs on %d processes "
		                     "(mpirun -np %d), which are the ranks: leave the key out, or "
		                     "run mpirun -np %lld", lz_scene_int(s, "ranks"), size, size,
		                     lz_scene_int(s, "ranks"));
	/* Only rank 0 runs the serial reference: the others need not build it. */
	int st = LZ_OK;
	if (rank != 0 && lz_scene_bool(s, "check") &&
	    ((st = lz_scene_set(s, "check=no", "lz-mpi (rank 0 checks)")) != LZ_OK ||
	     (st = lz_method_bind(&lz_method_pedmd, s)) != LZ_OK))
		return st;
	return lz_pedmd_scene_make(s, rank != 0, rank == 0, p);
}

/* The run's counters over all ranks, on rank 0 (lz_pedmd_counts_add). */
static lz_pedmd_counts counts_of_all(const lz_pedmd *r, int rank, int size)
{
	lz_pedmd_counts mine = lz_pedmd_counters(r), sum = {0};
	lz_pedmd_counts *all = rank == 0 ? malloc((size_t)size * sizeof *all) : NULL;
	if (rank == 0 && !all) {
		lz_error(LZ_ENOMEM, "no memory for the counters of %d ranks", size);
		abort_run(rank, LZ_ENOMEM);
	}
	MPI_Gather(&mine, (int)sizeof mine, MPI_BYTE, all, (int)sizeof mine, MPI_BYTE, 0,
	           MPI_COMM_WORLD);
	for (int k = 0; rank == 0 && k < size; k++)
		lz_pedmd_counts_add(&sum, &all[k]);
	free(all);
	return sum;
}

/* What a process holds. */
typedef struct {
	lz_scene *s;
	lz_pedmd_scene p;
	lz_pedmd_domains *d;
	lz_msg *msg;
	lz_pedmd *r;
	double pilot_ratio;  /* balance = pilot: the busiest rank's share, pilot cuts / even */
} lz_mpi_run;

/* Particles a round of gather() brings to rank 0, from all ranks together, and that
 * all ranks together send in a round of hand_over() (each one to the ranks that hold
 * its cell): the picture moves in pieces of 6.8 MB, never all at once. */
#define GATHER_ROUND 65536

/* A round's m particles written into out on rank 0, each once (seen[]): LZ_OK, or
 * LZ_EDOM naming one owned twice or unknown. *got counts them. */
static int file_round(lz_edmd *out, uint8_t *seen, const lz_pedmd_message *part, size_t m,
                      size_t *got)
{
	for (size_t k = 0; k < m; k++) {
		uint32_t i = part[k].id;
		if (i >= out->n || seen[i]++)
			return lz_error(LZ_EDOM, "particle %u is owned twice (or does not exist)", i);
		out->p[i] = part[k].p;
		++*got;
	}
	return LZ_OK;
}

/* The owned particles of every rank written on rank 0 into the system of its rank,
 * which then ends (lz_pedmd_release; its cells are not updated): the serial picture,
 * as lz_pedmd_sim_gather, in x->p.system on rank 0 (the others free their ranks and
 * keep no picture). Rank 0's own particles are
 * there already; the others' come in rounds of GATHER_ROUND / size from each rank.
 * LZ_OK, or an error on rank 0 when a particle came never or twice. Collective. */
static int gather(lz_mpi_run *x, int rank, int size)
{
	size_t N = lz_pedmd_particles(x->r), chunk = GATHER_ROUND / (size_t)size, got = 0;
	uint8_t *seen = rank == 0 ? calloc(N, 1) : NULL;
	lz_pedmd_message *part = malloc((rank == 0 ? (size_t)size : 1) * chunk * sizeof *part);
	int *count = malloc(2 * (size_t)size * sizeof *count);
	if ((rank == 0 && !seen) || !part || !count) {
		lz_error(LZ_ENOMEM, "no memory to gather %zu particles", N);
		abort_run(rank, LZ_ENOMEM);
	}
	for (uint32_t i = 0; rank == 0 && i < N; i++)
		got += seen[i] = lz_pedmd_role(x->r, i) == LZ_PEDMD_OWNED;
	int mine = rank == 0 ? 0 : (int)lz_pedmd_owned(x->r, NULL), rounds;
	int need = (int)(((size_t)mine + chunk - 1) / chunk);
	MPI_Allreduce(&need, &rounds, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
	MPI_Datatype type;
	MPI_Type_contiguous((int)sizeof *part, MPI_BYTE, &type);
	MPI_Type_commit(&type);
	int st = LZ_OK, *at = count + size;
	uint32_t from = 0;
	lz_edmd *out = rank == 0 ? lz_pedmd_release(x->r) : NULL;  /* its own are in place */
	if (rank == 0 && !out)
		abort_run(rank, LZ_ENOMEM);
	for (int k = 0; k < rounds; k++) {
		int n = rank == 0 ? 0 : (int)lz_pedmd_owned_part(x->r, &from, part, chunk);
		MPI_Gather(&n, 1, MPI_INT, count, 1, MPI_INT, 0, MPI_COMM_WORLD);
		for (int q = 0, sum = 0; rank == 0 && q < size; sum += count[q++])
			at[q] = sum;
		MPI_Gatherv(rank == 0 ? MPI_IN_PLACE : part, n, type, part, count, at, type, 0,
		            MPI_COMM_WORLD);
		if (rank == 0 && st == LZ_OK)
			st = file_round(out, seen, part, (size_t)(at[size - 1] + count[size - 1]), &got);
	}
	MPI_Type_free(&type);
	if (rank == 0 && st == LZ_OK && got != N)
		st = lz_error(LZ_EDOM, "the ranks own %zu of the %zu particles", got, N);
	if (rank != 0)
		lz_pedmd_free(x->r);
	x->p.system = out;  /* rank 0's picture; the others keep none */
	x->r = NULL;
	free(part);
	free(count);
	free(seen);
	return st;
}

/* The ranks that hold cell c under the cuts in d — its owner, then those with c as
 * HALO — into to[]; their number. */
static int holders(const lz_edmd *e, const lz_pedmd_domains *d, uint32_t c, int *to)
{
	to[0] = lz_pedmd_owner(d, c);
	return 1 + lz_pedmd_listeners(e, d, to[0], c, to + 1);
}

/* Buffers of the hand-over: what a round sends, sorted by rank, and what it receives;
 * count[], at[]: sent to each rank and where, then received from each and where;
 * fill[]: where the next one for each rank goes. */
typedef struct {
	lz_pedmd_message *part, *out, *in;
	size_t capout, capin;
	int *count, *at, *rcount, *rat, *fill;
} shares;

/* What this rank sends in a round of spread(): the particles of the start (rank 0 at
 * the set-up, start != NULL), or those it owned under the old cuts. */
typedef struct {
	const lz_edmd *start;
	uint32_t next;  /* the start's next particle */
	size_t from;    /* the next formerly owned one */
} source;

/* One round of spread(): at most `chunk` particles from src, each sent to the ranks
 * that hold its cell now, and what comes here taken. LZ_OK or an error. Collective. */
static int share_round(lz_pedmd *r, const lz_pedmd_domains *d, int size, source *src,
                       size_t chunk, shares *b, MPI_Datatype type)
{
	const lz_edmd *e = lz_pedmd_system(r);
	size_t n = src->start ? lz_pedmd_start_part(src->start, &src->next, b->part, chunk)
	                      : lz_pedmd_take_share(r, &src->from, b->part, chunk);
	size_t total = 0, got = 0;
	int to[27];
	memset(b->count, 0, (size_t)size * sizeof *b->count);
	for (size_t k = 0; k < n; k++)
		for (int h = holders(e, d, b->part[k].p.cell, to); h-- > 0;)
			b->count[to[h]]++;
	for (int q = 0; q < size; q++) {  /* <= 27 N < 2^31 for N < 2^26 */
		b->at[q] = b->fill[q] = (int)total;
		total += (size_t)b->count[q];
	}
	if (lz_pedmd_grow((void **)&b->out, &b->capout, total, sizeof *b->out))
		return LZ_ENOMEM;
	for (size_t k = 0; k < n; k++)
		for (int h = holders(e, d, b->part[k].p.cell, to); h-- > 0;)
			b->out[b->fill[to[h]]++] = b->part[k];
	MPI_Alltoall(b->count, 1, MPI_INT, b->rcount, 1, MPI_INT, MPI_COMM_WORLD);
	for (int q = 0; q < size; q++) {
		b->rat[q] = (int)got;
		got += (size_t)b->rcount[q];
	}
	int st = lz_pedmd_grow((void **)&b->in, &b->capin, got, sizeof *b->in), all;
	MPI_Allreduce(&st, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);  /* all or none */
	if (all != LZ_OK)
		return st != LZ_OK ? st : lz_error(LZ_ENOMEM, "another rank ran out of memory");
	MPI_Alltoallv(b->out, b->count, b->at, type, b->in, b->rcount, b->rat, type,
	              MPI_COMM_WORLD);
	return lz_pedmd_take_part(r, b->in, got);
}

/* Every rank takes its share under the cuts in d — the particles of its cells and
 * halo —, sent from src in rounds of at most `chunk` a rank (lz_pedmd_take_begin,
 * _part, _end), never the whole picture at once; then the ranks must own N together.
 * `mine`: how many particles src holds here. LZ_OK or an error. Collective. */
static int spread(lz_pedmd *r, const lz_pedmd_domains *d, int size, source *src, size_t mine,
                  size_t chunk)
{
	size_t N = lz_pedmd_particles(r);
	int need = (int)((mine + chunk - 1) / chunk), rounds;
	MPI_Allreduce(&need, &rounds, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
	shares b = {.part = malloc(chunk * sizeof *b.part),
	            .count = malloc(5 * (size_t)size * sizeof *b.count)};
	if (!b.part || !b.count)
		return lz_error(LZ_ENOMEM, "no memory to hand %zu particles over", N);
	b.at = b.count + size;
	b.rcount = b.at + size;
	b.rat = b.rcount + size;
	b.fill = b.rat + size;
	MPI_Datatype type;
	MPI_Type_contiguous((int)sizeof *b.part, MPI_BYTE, &type);
	MPI_Type_commit(&type);
	int st = lz_pedmd_take_begin(r);
	for (int k = 0; k < rounds && st == LZ_OK; k++)
		st = share_round(r, d, size, src, chunk, &b, type);
	MPI_Type_free(&type);
	free(b.part);
	free(b.out);
	free(b.in);
	free(b.count);
	if (st != LZ_OK)
		return st;
	if ((st = lz_pedmd_take_end(r)) != LZ_OK)
		return st;
	unsigned long long owned = lz_pedmd_owned(r, NULL), sum;
	MPI_Allreduce(&owned, &sum, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
	if (sum != N)
		return lz_error(LZ_EDOM, "after the hand-over the ranks own %llu of the %zu "
		                "particles", sum, N);
	return LZ_OK;
}

/* The new cuts in d: every particle from its owner under the old cuts to the ranks
 * that hold its cell now, GATHER_ROUND / size a rank a round. Collective. */
static int hand_over(lz_pedmd *r, const lz_pedmd_domains *d, int size)
{
	source src = {0};
	return spread(r, d, size, &src, lz_pedmd_owned(r, NULL), GATHER_ROUND / (size_t)size);
}

/* After a hand-over: the freed buffers (and at the start, the start) back to the
 * system, so that a process holds what its rank holds (glibc keeps freed memory
 * otherwise; elsewhere nothing). */
static void give_back(void)
{
#ifdef __GLIBC__
	malloc_trim(0);
#endif
}

/* balance = dynamic, at a cut lz_pedmd_balance_due names (every rank is there): the
 * load since the last look summed over the ranks, the same new cuts everywhere, and
 * when they pay, the particles handed over to the ranks that now hold their cells.
 * LZ_OK or an error. Collective. O(cells), and O(N) when the cuts move. */
static int move_cuts(lz_pedmd *r, lz_pedmd_domains *d, int rank, int size)
{
	size_t nc = d->ncells;
	double *load = malloc(nc * sizeof *load);
	int st = load ? lz_pedmd_load_since(r, load)
	              : lz_error(LZ_ENOMEM, "no memory for the load of %zu cells", nc);
	if (st != LZ_OK)
		abort_run(rank, st);
	MPI_Allreduce(MPI_IN_PLACE, load, (int)nc, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1];
	int moved = lz_pedmd_rebalance(d, load, r->p.threshold, cut);
	free(load);
	if (!moved)
		return LZ_OK;
	memcpy(d->cut, cut, (size_t)(size + 1) * sizeof *cut);
	st = hand_over(r, d, size);
	give_back();
	return st;
}

/* The two costs of a message that the stub's virtual-time policy models (lz/msg.h),
 * measured on this back-end by a ping-pong of ranks 0 and 1 before the run, so that
 * `make bench` can feed the model with them: cost, rank 0's time inside a send and
 * inside the poll that returns the answer (the mean of the two); latency, what is left
 * of each leg of a round trip (a leg is a cost at each end and a latency). Messages of
 * the engine's size, one in flight at a time (as the engine's border news: a burst
 * would measure the back-end's queue, not a message); all are received, so the cut's
 * counters stay balanced. The other ranks take no part. */
typedef struct {
	double cost, latency;
} probe_result;
enum { PROBE_PINGS = 4000 };

/* Wait for one message; the time of the poll that returned it in *busy. */
static int probe_recv(lz_msg *msg, lz_pedmd_message *m, double *busy)
{
	int from, got;
	size_t n;
	double t;
	do {
		t = lz_msg_clock(msg);
		got = lz_msg_poll(msg, &from, m, sizeof *m, &n);
	} while (got == 0);
	*busy = lz_msg_clock(msg) - t;
	return got < 0 ? got : LZ_OK;
}

static probe_result probe(lz_msg *msg, int rank, int size)
{
	probe_result res = {0, 0};
	lz_pedmd_message m = {0};
	int st = LZ_OK, other = 1 - rank;
	if (size < 2 || rank > 1)
		return res;
	double busy = 0, q, t0 = lz_msg_clock(msg);
	for (int k = 0; k < PROBE_PINGS && st == LZ_OK; k++) {
		double ts = lz_msg_clock(msg);
		if (rank == 0 && (st = lz_msg_send(msg, other, &m, sizeof m)) == LZ_OK) {
			busy += lz_msg_clock(msg) - ts;
			st = probe_recv(msg, &m, &q);
			busy += q;
		} else if (rank == 1 && (st = probe_recv(msg, &m, &q)) == LZ_OK) {
			st = lz_msg_send(msg, other, &m, sizeof m);
		}
	}
	double round = (lz_msg_clock(msg) - t0) / PROBE_PINGS;
	if (st != LZ_OK)
		abort_run(rank, st);
	res.cost = busy / (2.0 * PROBE_PINGS);
	res.latency = fmax(round / 2 - 2 * res.cost, 0);
	return res;
}

/* The processes' memory in MiB, on rank 0: what[0] rank 0's own, what[1] the largest
 * of the others' (0 on one process) — their peak resident size (getrusage: kB on
 * Linux; the set-up included), or (now = 1) what each holds now (/proc/self/statm:
 * resident pages; 0 where that file is not). Collective. */
static void memory_mib(int now, int rank, int size, double what[2])
{
	struct rusage u;
	unsigned long pages = 0, resident = 0;
	double mine = !now && getrusage(RUSAGE_SELF, &u) == 0 ? (double)u.ru_maxrss / 1024 : 0;
	FILE *f = now ? fopen("/proc/self/statm", "r") : NULL;
	if (f && fscanf(f, "%lu %lu", &pages, &resident) == 2)
		mine = (double)resident * (double)sysconf(_SC_PAGESIZE) / 1048576;
	if (f)
		fclose(f);
	double other = rank == 0 ? 0 : mine;
	what[0] = mine;
	MPI_Reduce(&other, &what[1], 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
	if (size == 1)
		what[1] = 0;
}

static void report(const lz_scene *s, const lz_pedmd_scene *p, int size,
                   const lz_pedmd_counts *c, double wall, probe_result cost, double pilot,
                   const double peak[2], const double held[2])
{
	const lz_edmd *e = p->system;
	printf("lz-mpi: scene %s, %zu %s, %d ranks along the %s curve\n", lz_scene_name(s), e->n,
	       e->dim == 3 ? "spheres" : "disks", size,
	       p->kind == LZ_PEDMD_ROWS ? "row" : "Morton");
	printf("ranks                 %d\n", size);
	printf("particles             %zu\n", e->n);
	printf("simulated time        %.6g τ\n", p->t_stop);
	printf("committed events      %llu\n", (unsigned long long)c->committed);
	printf("processed events      %llu\n", (unsigned long long)c->processed);
	printf("efficiency            %.4f\n",
	       c->processed ? (double)c->committed / (double)c->processed : 0.0);
	printf("windows               %llu\n", (unsigned long long)c->windows);
	printf("rollbacks             %llu\n", (unsigned long long)c->rollbacks);
	printf("conservative steps    %llu\n", (unsigned long long)c->conservative);
	if (p->params.balance > 0)
		printf("cut moves             %llu\n", (unsigned long long)c->balances);
	if (!isnan(pilot))
		printf("pilot busiest share   %.4f (pilot cuts over even cuts)\n", pilot);
	printf("parallel wall time    %.4f s\n", wall);
	printf("committed events/s    %.4g\n", wall > 0 ? (double)c->committed / wall : 0.0);
	double n = (double)e->n / 1048576;  /* MiB over this: bytes a particle */
	printf("peak memory           %.1f MiB on rank 0 (%.0f bytes a particle; it builds the "
	       "start)\n", peak[0], peak[0] / n);
	printf("run memory            %.1f MiB on rank 0 (resident at the run's end; %.0f bytes "
	       "a particle)\n", held[0], held[0] / n);
	if (size > 1)
		printf("peak memory, others   %.1f MiB a process (the largest; %.0f bytes a "
		       "particle)\nrun memory, others    %.1f MiB a process (the largest; %.0f "
		       "bytes a particle)\n", peak[1], peak[1] / n, held[1], held[1] / n);
	if (size > 1)
		printf("message cost          %.3g s (send or receive; %d ping-pongs of ranks 0, 1)\n"
		       "message latency       %.3g s\n", cost.cost, PROBE_PINGS, cost.latency);
	fflush(stdout);
}


/* The start's box, cells and clock from rank 0 to every process (only scalars: its
 * arrays stay where they are), into *shape. Collective. */
static void share_shape(const lz_edmd *start, lz_edmd *shape)
{
	if (start)
		*shape = *start;
	MPI_Bcast(shape, (int)sizeof *shape, MPI_BYTE, 0, MPI_COMM_WORLD);
	shape->list = NULL;
	shape->next = NULL;
	shape->p = NULL;
	shape->ev = NULL;
	shape->heap = NULL;
	shape->cal = NULL;
	shape->lists = NULL;
}

/* balance = pilot on rank 0, which holds the start; its cuts (when they pay) and ratio
 * to everyone. The status as rank 0's, agreed. */
static int pilot(lz_mpi_run *x, int rank, int size, uint32_t *cut, int *moved)
{
	int st = LZ_OK, agreed;
	if (rank == 0 && lz_scene_enum(x->s, "balance") == 1)
		st = lz_pedmd_scene_pilot(&x->p, cut, moved, &x->pilot_ratio);
	if (agree(st, rank, size, &agreed))
		return agreed;
	MPI_Bcast(moved, 1, MPI_INT, 0, MPI_COMM_WORLD);
	MPI_Bcast(cut, LZ_PEDMD_RANKS_MAX + 1, MPI_UINT32_T, 0, MPI_COMM_WORLD);
	MPI_Bcast(&x->pilot_ratio, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
	return LZ_OK;
}

/* Scene, seeds, system and domains, agreed on after every step that can fail (the
 * steps between are collective): the agreed status. Only rank 0 builds the start; on
 * one process the rank takes it itself (lz_pedmd_adopt), on more every rank opens
 * empty and takes its share of it from rank 0, in rounds (spread), and rank 0 frees
 * it: no process but rank 0 ever holds all N. */
static int setup(int argc, char **argv, int rank, int size, lz_mpi_run *x)
{
	int agreed, moved = 0;
	if (agree(load(argc, argv, size, &x->s), rank, size, &agreed) ||
	    agree(share_seeds(x->s, rank), rank, size, &agreed) ||
	    agree(make(x->s, rank, size, &x->p), rank, size, &agreed))
		return agreed;
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1] = {0};
	int st = pilot(x, rank, size, cut, &moved);
	if (st != LZ_OK)
		return st;
	lz_edmd shape;
	share_shape(x->p.system, &shape);
	if (!(x->d = lz_pedmd_domains_alloc(&shape, size, x->p.kind)))
		st = last_code ? last_code : LZ_EINVAL;
	if (st == LZ_OK && moved)
		memcpy(x->d->cut, cut, (size_t)(size + 1) * sizeof *cut);
	if (agree(st, rank, size, &agreed))
		return agreed;
	if (!(x->msg = lz_msg_mpi_open()))  /* collective: a failure here stops everyone */
		abort_run(rank, last_code);
	if (size == 1) {  /* the rank takes the system itself: one copy of it, not two */
		x->r = lz_pedmd_adopt(x->p.system, x->d, x->msg, &x->p.params);
		x->p.system = NULL;
		agree(x->r ? LZ_OK : last_code, rank, size, &agreed);
		return agreed;
	}
	x->r = lz_pedmd_open(&shape, x->d, x->msg, &x->p.params);
	if (agree(x->r ? LZ_OK : last_code, rank, size, &agreed))
		return agreed;
	source src = {.start = x->p.system};
	if ((st = spread(x->r, x->d, size, &src, rank == 0 ? shape.n : 0, GATHER_ROUND)) != LZ_OK)
		abort_run(rank, st);  /* the others may wait in a round: stop them */
	lz_edmd_free(x->p.system);
	x->p.system = NULL;
	give_back();
	return LZ_OK;
}

/* Free everything (collectively: the back-end's communicator) and exit with st. */
static int quit(lz_mpi_run *x, int st)
{
	lz_pedmd_free(x->r);
	lz_msg_mpi_close(x->msg);
	lz_pedmd_domains_free(x->d);
	lz_pedmd_scene_free(&x->p);
	lz_scene_free(x->s);
	MPI_Finalize();
	return exit_status(st);
}

int main(int argc, char **argv)
{
	MPI_Init(&argc, &argv);
	int rank, size;
	MPI_Comm_rank(MPI_COMM_WORLD, &rank);
	MPI_Comm_size(MPI_COMM_WORLD, &size);
	lz_set_error_handler(record);
	lz_mpi_run x = {.pilot_ratio = NAN};
	int st = setup(argc, argv, rank, size, &x);
	if (st != LZ_OK)
		return quit(&x, st);

	probe_result cost = probe(x.msg, rank, size);
	MPI_Bcast(&cost, (int)sizeof cost, MPI_BYTE, 0, MPI_COMM_WORLD);

	/* The parallel part. A waiting rank yields its core (mpirun --oversubscribe). */
	MPI_Barrier(MPI_COMM_WORLD);
	double t0 = MPI_Wtime();
	lz_work state = LZ_WORK_BUSY;
	while (state != LZ_WORK_DONE) {
		if (lz_pedmd_balance_due(x.r, x.p.t_stop) &&
		    (st = move_cuts(x.r, x.d, rank, size)) != LZ_OK)
			abort_run(rank, st);
		if ((st = lz_pedmd_work(x.r, x.p.t_stop, &state)) != LZ_OK)
			abort_run(rank, st);
		if (state == LZ_WORK_WAIT)
			sched_yield();
	}
	double wall = MPI_Wtime() - t0, slowest = wall;
	MPI_Reduce(&wall, &slowest, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
	double held[2], peak[2];
	memory_mib(1, rank, size, held);  /* before the picture is gathered */

	/* The results, on rank 0. */
	lz_pedmd_counts c = counts_of_all(x.r, rank, size);
	st = gather(&x, rank, size);
	memory_mib(0, rank, size, peak);  /* check = yes: the serial reference is in it too */
	if (rank == 0 && st == LZ_OK)
		report(x.s, &x.p, size, &c, slowest, cost, x.pilot_ratio, peak, held);
	if (rank == 0 && st == LZ_OK && x.p.check && (st = lz_pedmd_scene_serial(&x.p)) == LZ_OK) {
		size_t k = lz_pedmd_scene_differ(x.p.system, x.p.reference);
		if (k == 0)
			printf("identical to the serial run: yes\n");
		else
			printf("identical to the serial run: no: %zu particles differ\n", k);
		if (k)
			st = lz_error(LZ_EPHYS, "%zu of the %zu particles end elsewhere than in the "
			              "serial run: the parallel engine is wrong", k, x.p.system->n);
	}
	fflush(stdout);
	if (rank == 0 && st != LZ_OK)
		fprintf(stderr, "lz-mpi: %s\n", lz_error_message());
	MPI_Bcast(&st, 1, MPI_INT, 0, MPI_COMM_WORLD);
	return quit(&x, st);
}
