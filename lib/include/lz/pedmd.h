/* lz/pedmd.h — optimistic parallel event-driven hard spheres (Miller & Luding,
 * J. Comput. Phys. 193, 306 (2004), §III): the serial engine of lz/edmd.h, cut into P
 * domains that run ahead optimistically, save their state, and roll back when a
 * message shows they were wrong.
 *
 * Domains. The cells of the serial engine are laid along a curve — row by row (slabs
 * along the slowest axis) or in Morton order (the paper's fig. 4, compact domains) —
 * and the curve is cut into P runs: rank r owns the cells at curve places cut[r] ..
 * cut[r+1]-1. On rank r a cell is INTERIOR (owned, its whole 3^dim block owned), BORDER
 * (owned, some neighbour not), HALO (not owned, next to an owned cell: the particles
 * there are GHOSTS, copies of their owners' records) or FAR. A prediction for an owned
 * particle reads only its block, so owned and ghost particles are all it needs.
 *
 * One rank is a lz_edmd of the particles it holds, of which only the owned and the
 * ghosts are in cells; the heap holds the owned ones. It runs the serial engine's own predictions (lz_edmd_predict) and
 * bounces, so a rank computes the same bits as the serial run would for every event,
 * provided that its ghosts are up to date. Owners keep them up to date: whenever an
 * owned particle in a BORDER cell changes (its state, its cell, its predicted event),
 * a message goes to the ranks that hold its cell as HALO — LEAVE when it leaves their
 * halo, MIGRATE to the new owner when it crosses into another rank's cell.
 *
 * Cross-border collisions run on both sides, with the same bits. The serial heap
 * would take the earlier of i's and j's predicted events; here i's owner knows j's
 * event from its messages, and a ghost's event aimed at an owned particle i (with i's
 * current count) takes i's place in the heap when it is the earlier: both ranks then
 * collide i and j at the same time, and the bounce is symmetric bit for bit. Such a
 * replicated collision is committed once (by the rank owning the smaller number).
 *
 * Optimism. Between two synchronisations (a WINDOW: from T to T_end) every rank runs
 * its events and the messages it receives in time order, without waiting. A message
 * may arrive LATE — with a time before what the rank has already done. It is harmless
 * unless the rank has used what it changes; it is a CAUSALITY ERROR when:
 *   - a prediction after the message's time read a cell the message changes (the
 *     ghost's old or new cell: `read` keeps the last time each cell near a border was
 *     read);
 *   - a migrated particle must be predicted at a time some particle of its block has
 *     already passed;
 *   - a ghost's event aimed at an owned particle falls before the rank's clock.
 * At the window's end the ranks meet at a consistent cut (no message in flight:
 * every rank idle and the sums of messages sent and received equal twice in a row)
 * and decide together: no error anywhere — COMMIT (the saved state is discarded,
 * fossil collection); an error — ROLLBACK every rank to the saved state and run the
 * window again up to the earliest error, its events included (the paper's
 * synchronisation barrier at the error time). An error cannot come again at a
 * window's end (nothing in the window is later than it), so the errors a window meets
 * move strictly earlier and progress is certain (no livelock). An error at the
 * window's very start, which the protocol never makes, would take a CONSERVATIVE
 * STEP: only the events at the global earliest time, which nothing can overtake. The
 * rank that finds an error tells the others (HALT), and they stop the lost window.
 *
 * State saving. A window saves the first version of every particle record it changes
 * (its record, event, role and events), the rank's counters and the old read stamps;
 * a rollback writes them back, each particle into its cell list and the heap, in
 * O(log N) a particle: it costs what the window touched. Reverse computation would undo each
 * event instead, but a bounce is not exactly invertible in floating point.
 *
 * Load balancing. Every rank counts the committed events of each cell (load). New
 * cuts along the curve give every rank the same share of the load (lz_pedmd_rebalance);
 * a run started with those cuts is balanced for a system whose load stays where it
 * was; params.balance also moves them during a run, at a cut every so many windows,
 * the particles changing owners there: every rank adds what its cells committed since
 * the last look (lz_pedmd_load_since), all see the same sum and the same new cuts, and
 * each takes its share of the serial picture that the owned particles of all ranks
 * make (lz_pedmd_owned, lz_pedmd_take) — in one process (lz_pedmd_recut) or over MPI
 * (lz-mpi: a sum, then each particle sent only to the ranks that hold its cell under
 * the new cuts, in rounds: lz_pedmd_take_begin, _share, _part, _end).
 *
 * What a rank need not hold. An owned particle's event may aim at a particle the rank
 * does not hold: its record there is an old one, or LZ_PEDMD_UNKNOWN. Such an event is
 * stale, as it is in the serial run. A prediction looks only at the block of i's cell,
 * and a collision that is i's next event comes before i leaves that cell; the partner,
 * in the block when predicted and touching i at the event, moves on a straight line
 * between two points of the block (a box) and stays in it unless it collides or
 * bounces, which changes its count; and the block is owned or HALO, so a partner the
 * rank does not hold has a new count. Under gravity a path curves and may leave the
 * block and come back with its count: it comes back as a ghost (its owner's news)
 * before the event, or that news is late and rolls the window back.
 *
 * The clock is re-based (lz_edmd_rebase) at absolute multiples of `rebase` only, the
 * same times as the serial reference (rebase_auto = 0), so that both round alike:
 * the committed events, their count, and the final positions and velocities equal the
 * serial run's bit for bit.
 *
 * Local numbering (params.compact = 1, what lz-mpi and `lz run` use). A rank holds
 * its particles in SLOTS 0 .. M-1 of its own system — the owned, the ghosts, and those
 * it has heard of (a partner named in a message, a particle it handed over) —, with
 * gid[slot] the particle's number and an index from number to slot (a hash table).
 * Inside the rank everything speaks of slots, as the serial engine speaks of
 * particles: cells, heap, events, saved versions. Only what crosses the rank's edge
 * speaks of numbers: a message's particle and its event's partner are translated when
 * sent and when received (lz_pedmd_outgoing, lz_pedmd_incoming: a particle met for
 * the first time gets a blank slot, ABSENT, count LZ_PEDMD_UNKNOWN), and so are the
 * log, the audit and the pictures. Slots are never given back during a run (an event
 * may still aim at one); moving the cuts (lz_pedmd_take) keeps only those it then
 * holds and names (lz_pedmd_compact). Where
 * the order of particles decides something — which side of a replicated collision
 * commits it, the order of waiting messages at one time, of a cell's list after a
 * hand-over, of the heap's filling — it is the order of the numbers, so a rank in
 * local numbering runs exactly what a rank with a slot for every particle
 * (params.compact = 0, slot i = particle i: the graded tests' hand-made states) runs.
 *
 * Units as lz/edmd.h. Memory of a rank in local numbering: about 160 bytes a slot (its
 * system's record, event, list link and heap node; role, own and ghost events, last
 * message, save mark and number; the index), an eighth more slots than it held at
 * the start; and for the cells it holds (owned and HALO), its list head, read stamp
 * and its mark, and load — 28 bytes, in pages that take memory only where written
 * (lz_bigmem_sparse): the lists and stamps of FAR cells are never written nor read.
 * Every rank keeps, for every cell, its class (1 byte), a near bit and the curve (8
 * bytes, lz_pedmd_domains). So memory falls as 1/P but for the curve and the classes.
 * With params.compact = 0 a rank has arrays for all N particles instead: its system
 * (a copy of the start, or the start itself with lz_pedmd_adopt) and 45 bytes a
 * particle of its own. Plus what a window saves.
 */
#ifndef LZ_PEDMD_H
#define LZ_PEDMD_H

#include <stddef.h>
#include <stdint.h>

#include "lz/edmd.h"
#include "lz/msg.h"

enum { LZ_PEDMD_ROWS, LZ_PEDMD_MORTON };  /* the curve */

/* Cell classes on one rank (lz_pedmd_classify). */
enum { LZ_PEDMD_FAR, LZ_PEDMD_HALO, LZ_PEDMD_INTERIOR, LZ_PEDMD_BORDER };

/* Where a rank is in the window protocol of lz_pedmd_work: about to begin a window,
 * running it, at the cut waiting for the verdict, or done. */
enum { LZ_PEDMD_BEGIN, LZ_PEDMD_RUN, LZ_PEDMD_DECIDE, LZ_PEDMD_DONE };

/* Particle roles on one rank. */
enum { LZ_PEDMD_ABSENT, LZ_PEDMD_OWNED, LZ_PEDMD_GHOST };

/* The count in the record of a particle the rank has not held since it was set up or
 * took its share of a picture (lz_pedmd_take): no partner count equals it, so an event
 * aimed at such a particle is stale — as it is in the serial run (see the header). */
#define LZ_PEDMD_UNKNOWN UINT32_MAX

/* The most ranks. */
#define LZ_PEDMD_RANKS_MAX 256

/* The decomposition: the cells along a curve, cut into P runs. Invariants:
 * curve[place[c]] = c for every cell; cut[0] = 0 < cut[1] < ... < cut[P] = ncells. */
typedef struct {
	int P;
	int kind;            /* LZ_PEDMD_ROWS or LZ_PEDMD_MORTON */
	size_t ncells;
	uint32_t *curve;     /* curve[k]: the cell at place k */
	uint32_t *place;     /* place[c]: where cell c lies on the curve */
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1];
} lz_pedmd_domains;

/* An event as the owner predicted it: time (in the common time base), partner
 * (as lz_edmd_event) and the partner's count. */
typedef struct {
	double t;
	lz_edmd_event ev;
} lz_pedmd_event;

/* A message between ranks: what changed on a particle, and when. HALT is the
 * protocol's own (lz_pedmd_work; it never reaches lz_pedmd_apply): its sender found a
 * causality error at t, so the window will be rolled back and the others stop it. */
enum { LZ_PEDMD_STATE, LZ_PEDMD_MIGRATE, LZ_PEDMD_LEAVE, LZ_PEDMD_HALT };
typedef struct {
	double t;              /* the sender's clock when it changed */
	uint32_t id;           /* the particle: its number as it travels, its slot once
	                          received (lz_pedmd_incoming) */
	uint32_t kind;         /* STATE, MIGRATE or LEAVE */
	lz_edmd_particle p;    /* its record after the change (p.cell: its cell now) */
	lz_pedmd_event event;  /* its next event as its owner predicted it */
} lz_pedmd_message;

/* One committed (or processed) event, for the checks against the serial run. */
enum { LZ_PEDMD_COLLISION, LZ_PEDMD_CROSSING, LZ_PEDMD_BOUNCE, LZ_PEDMD_STALE };
typedef struct {
	double t;       /* absolute time */
	uint32_t i, j;  /* particles by number (j = i for one-particle events; i < j for
	                   collisions) */
	uint32_t kind;
	uint32_t cell;  /* the cell of particle i (the smaller number, which the noting
	                   rank owns) after the event: where the work was done, for the
	                   load of lz_pedmd_rebalance */
} lz_pedmd_record;

/* The first version, in this window, of one particle on this rank. */
typedef struct {
	uint32_t id;
	uint8_t role, in_heap;
	lz_edmd_particle p;
	lz_edmd_event ev;
	lz_pedmd_event own, ghost;
	double key, heard;
} lz_pedmd_saved;

/* A read stamp as it was before this window first raised it (lz_pedmd_read_at). */
typedef struct {
	uint32_t cell;
	double read;
} lz_pedmd_stamp;

/* Counters of one rank. */
typedef struct {
	uint64_t processed;      /* events carried out, rolled back ones included */
	uint64_t committed;      /* events committed (replicated collisions once) */
	uint64_t windows, rollbacks, conservative, balances;
	uint64_t late_harmless;  /* messages that came late but changed nothing used */
	uint64_t saved_bytes;    /* the most a window saved */
	uint64_t rechecks;       /* windows run twice by the rollback check */
	uint64_t collisions, crossings, bounces, stale;  /* committed, by kind */
	double virial;           /* committed collisions' virial (this rank's share) */
} lz_pedmd_counts;

/* What a run is asked to do. */
typedef struct {
	double window;      /* the first window's length (> 0); it adapts: x grow after a
	                       commit, /2 after a rollback, within [window/64, 64 window] */
	double rebase;      /* re-base the clock at absolute multiples of this (> 0) */
	int balance;        /* new cuts from the load since the last ones every this many
	                       windows (0: never), moved when they pay (threshold): the
	                       driver of the ranks (lz_pedmd_sim_run, lz-mpi) asks
	                       lz_pedmd_balance_due at every cut */
	double threshold;   /* ... when the largest load improves by this fraction */
	int log;            /* 1: keep the committed events (lz_pedmd_log) */
	int work;           /* events per turn of the work function (> 0) */
	int recheck;        /* 1: the rollback check — every window that would commit is
	                       rolled back (the restored state must equal the window's
	                       start) and run again (as the back-end then schedules it),
	                       and must end in the same state and events; else the run
	                       fails with LZ_EDOM. Costs a second run and O(N) per window */
	double grow;        /* the window's growth after a commit, in (1, 2]: the adaptation
	                       settles where a fraction ln grow / (ln grow + ln 2) of the
	                       windows is rolled back (1.125: one in seven, for windows of a
	                       few hundred events, where the cut is dear; 1.02: one in 36,
	                       for windows of 10^4 events and more, where a rollback is) */
	int compact;        /* 1: LOCAL NUMBERING — the rank holds only the particles it has
	                       heard of, in slots 0 .. M-1 of its system (see "Local
	                       numbering" above), so that its memory falls as 1/P; 0: a slot
	                       for every particle, slot i = particle i (the graded tests'
	                       hand-made states read the rank's arrays so) */
} lz_pedmd_params;

/* One rank. Invariants between events: an OWNED particle lies in an owned cell and
 * is in the heap, keyed by the earlier of its own prediction (own[i]) and the events
 * of ghosts aimed at it with its current count; a GHOST lies in a HALO cell with its
 * owner's record and event (ghost[i]); every other particle is ABSENT (in no cell, its
 * record meaningless). Times are in the common time base (e->t_base, the same on
 * every rank), the window's bounds absolute. */
typedef struct lz_pedmd {
	lz_edmd *e;                   /* its slots (compact), or all N particles */
	const lz_pedmd_domains *d;
	lz_msg *msg;
	lz_pedmd_params p;
	int rank;
	uint8_t *cls;                 /* the class of every cell for this rank */
	uint64_t *near;               /* bit c set: cell c's block holds a HALO or BORDER cell
	                                 (a bit a cell, so that it stays in cache: every
	                                 prediction asks) */
	double *read;                 /* HALO and BORDER cells: the last time a prediction
	                                 read the cell (lz_pedmd_read_at) */
	uint32_t *rmark;              /* rmark[c] == epoch: read[c] raised this window, its
	                                 old stamp in stamps */
	lz_pedmd_stamp *stamps;
	size_t nstamps, capstamps;
	uint8_t *role;                /* every particle's role */
	lz_pedmd_event *own;          /* OWNED: its own prediction; else own[i].t is when
	                                 this rank last handed it over (-INFINITY: never) */
	lz_pedmd_event *ghost;        /* GHOST: its owner's prediction */
	double *heard;                /* the time of the last message applied about the
	                                 particle (-INFINITY: none): an older one that
	                                 arrives after it (from a former owner) is stale */
	double clock;                 /* the latest time the rank has reached (relative);
	                                 e->now equals it except while a late message is
	                                 applied at its own, earlier time */
	/* messages that wait for the rank's clock: a min-heap by time */
	lz_pedmd_message *wait;
	size_t nwait, capwait;
	/* the window */
	double T, t_end;              /* absolute; events with t_base + t <= t_end run */
	double t_error;               /* the earliest causality error (INFINITY: none) */
	double width;                 /* the next window's length */
	/* state saving: particles saved this window (mark[i] == epoch), and the rest */
	uint32_t epoch;
	uint32_t *mark;
	lz_pedmd_saved *saved;
	size_t nsaved, capsaved;
	lz_edmd snap;                 /* the system's scalars at the window's start */
	double clock0;                /* the rank's clock then */
	double next0;                 /* and the time of its first event or message then
	                                 (absolute): a conservative step goes to the
	                                 earliest of these over all ranks */
	lz_pedmd_message *wait0;      /* the waiting messages then */
	size_t nwait0, capwait0;
	/* the events of this window, and the committed ones */
	lz_pedmd_record *wlog, *clog;
	size_t nwlog, capwlog, nclog, capclog;
	uint64_t wcommit;             /* events of this window it would commit */
	double wvirial;               /* and their virial */
	double *load;                 /* per cell: committed events noted with that cell */
	int nomem;                    /* 1: the window log or the stamps could not grow
	                                 (lz_pedmd_work then fails with LZ_ENOMEM) */
	lz_pedmd_counts counts;
	/* the protocol (pedmd_lib.c) */
	int phase;                    /* LZ_PEDMD_BEGIN .. LZ_PEDMD_DONE */
	int in_round, woke, rounds, rebase_at_end, forced;
	int halted;                   /* 1: this window's error is known to the others */
	double last_sum[3];
	double forced_end;            /* the next window's end, set at a cut (NAN: none) */
	/* the rollback check (params.recheck) */
	int rerun;                    /* 1: this window runs the second time */
	uint64_t print0, print1;      /* fingerprints: the window's start, its first end */
	int failed;                   /* an LZ_E code lz_pedmd_work returns (lz_error set) */
	/* moving cuts (params.balance) */
	uint64_t next_balance;        /* the windows begun at the next look at the load */
	double *load0;                /* load[] at the last look (NULL: none yet) */
	uint32_t *former;             /* between lz_pedmd_take_begin and _end: the particles
	                                 the rank owned under the old cuts */
	size_t nformer, capformer;
	/* local numbering (params.compact; pedmd_slots.c) */
	size_t N;                     /* the particles of the whole system */
	size_t nslots;                /* slots in use, 0 .. nslots-1 (N when not compact);
	                                 e->n slots exist, the rest blank and ABSENT */
	uint32_t *gid;                /* gid[slot]: the particle's number (NULL: slot =
	                                 number) */
	uint64_t *index;              /* number -> slot: open addressing, hcap entries (a
	                                 power of 2, at most three quarters full), each the
	                                 number and the slot (pedmd_slots.c) */
	size_t hcap;
	int hbits;                    /* hcap = 2^hbits */
} lz_pedmd;

/* ---- graded (solutions/06-parallel/pedmd.c) ---- */

/* The rank that owns cell c: the r with cut[r] <= place[c] < cut[r+1]. O(log P). */
int lz_pedmd_owner(const lz_pedmd_domains *d, uint32_t c);

/* The class of every cell of e's grid for rank `rank` into cls[ncells]: INTERIOR or
 * BORDER when owned (BORDER when some cell of its block is owned by another rank),
 * HALO when not owned but in the block of an owned cell, FAR otherwise. O(ncells ·
 * 3^dim · log P). */
void lz_pedmd_classify(const lz_edmd *e, const lz_pedmd_domains *d, int rank, uint8_t *cls);

/* The ranks other than `rank` that own a cell of cell c's block — those that hold c
 * as HALO and must hear of every change there — each once, in increasing order, into
 * out[]; their number. O(3^dim · log P). */
int lz_pedmd_listeners(const lz_edmd *e, const lz_pedmd_domains *d, int rank, uint32_t c,
                       int *out);

/* Carry out rank r's earliest event (its heap's top), if it is no later than r's
 * window end, as lz_edmd_step would, but on a rank: a partner may be a ghost (the
 * collision is replicated: both are bounced, only owned particles predicted again);
 * a crossing into a cell another rank owns hands the particle over (MIGRATE) and
 * keeps it here as a ghost; every change of an owned particle in a BORDER cell is
 * sent to the cell's listeners (lz_pedmd_announce); the event counts as processed,
 * and goes into the window's log (lz_pedmd_note) once — a replicated collision on
 * the rank that owns the smaller of the two numbers. *did = 1 when an event was
 * carried out, 0 when none is due before the window ends. LZ_OK or an LZ_E code
 * (a message that could not be sent). O(log N + messages). */
int lz_pedmd_step(lz_pedmd *r, int *did);

/* Apply message m, which has arrived at rank r: a ghost's new state and event
 * (STATE), a particle handed over (MIGRATE), a ghost gone (LEAVE). A message later
 * than r's clock waits (it is queued and applied in time order); an earlier one is
 * applied at once when nothing r has done used what it changes, and otherwise marks
 * r's CAUSALITY ERROR at the message's time (r then stops carrying out events until
 * the cut). Returns LZ_OK or an LZ_E code (an error in the data, not causality).
 * O(block). */
int lz_pedmd_apply(lz_pedmd *r, const lz_pedmd_message *m);

/* Before particle i (present on r or not) is changed for the first time in this
 * window, save its version (lz_pedmd_saved): LZ_OK, or LZ_ENOMEM; O(1). Roll the rank
 * back to the window's start: every saved version written back — its record, events
 * and role, its place in the cell lists and the heap —, the system's scalars (snap),
 * the clock, the queue of waiting messages and the read stamps (lz_pedmd_unread) as
 * they were. O(saved · log N + stamps + waiting): a rollback costs what the window
 * changed, never O(N). */
int lz_pedmd_save(lz_pedmd *r, uint32_t i);
void lz_pedmd_restore(lz_pedmd *r);

/* The decision at a cut. t_error: the earliest causality error on any rank (INFINITY:
 * none); T: the window's start; t_next: the earliest event or message anywhere.
 * COMMIT when there was no error; ROLLBACK with the next window ending at t_error
 * (its events included) when t_error > T; CONSERVATIVE (the next window ends at
 * t_next, events at exactly t_next only) when the error came at T or before, and a
 * window cannot be shortened further. *t_end gets the next window's end for ROLLBACK and CONSERVATIVE.
 * O(1). */
enum { LZ_PEDMD_COMMIT, LZ_PEDMD_ROLLBACK, LZ_PEDMD_CONSERVATIVE };
int lz_pedmd_decide(double t_error, double T, double t_next, double *t_end);

/* New cuts from the committed events of every cell (load[c], c in the grid): cut the
 * curve where the running total of load along it reaches k/P of the whole (every rank
 * at least one cell), into new_cut[0 .. P]. Returns 1 when the largest rank load of
 * the new cuts is at least a fraction `threshold` below that of the old ones (then
 * the cuts should move), else 0 (new_cut = the old cuts). O(ncells). */
int lz_pedmd_rebalance(const lz_pedmd_domains *d, const double *load, double threshold,
                       uint32_t *new_cut);

/* ---- what the graded functions build on (library) ---- */

/* Predict owned particle i again at e->now (lz_edmd_predict), keep that as own[i],
 * let an earlier ghost event aimed at i take its place in the heap, and note the
 * cells the prediction read (read[]); i is saved first. LZ_OK, or LZ_ENOMEM; a key
 * before the rank's clock is a causality error (lz_pedmd_late). O(block). */
int lz_pedmd_predict(lz_pedmd *r, uint32_t i);

/* Recompute owned particle i's key from own[i] and the ghosts' events aimed at it
 * (after a ghost's event changed), i saved first: as lz_pedmd_predict without the
 * prediction. O(block). */
int lz_pedmd_retarget(lz_pedmd *r, uint32_t i);

/* Tell the ranks that hold owned particle i's cell as HALO what it is now (STATE),
 * and those that held its old cell `from` (when it moved, else from = its cell) but
 * not the new one that it left (LEAVE). `to_owner` >= 0: that rank owns the new cell
 * and gets MIGRATE; the new cell's other listeners then hear from the new owner once
 * it has predicted the particle, not from here. t: the time of the change. LZ_OK or
 * an LZ_E code. */
int lz_pedmd_announce(lz_pedmd *r, uint32_t i, uint32_t from, int to_owner, double t);

/* Record the causality error at time t (relative): the rank stops carrying out events
 * until the cut. Returns LZ_OK (a causality error is not a failure of the call). */
int lz_pedmd_late(lz_pedmd *r, double t);

/* An event (relative time t) this window will commit, if it commits: counted (with a
 * collision's virial, and in the load of the cell of the smaller of i and j) and
 * appended to the window's log (no memory: r->nomem, and lz_pedmd_work fails). */
void lz_pedmd_note(lz_pedmd *r, double t, uint32_t i, uint32_t j, uint32_t kind,
                   double virial);

/* Room for entries 0 .. n of a growing array *v of *cap entries of `size` bytes
 * (doubling): n is the number in use when one more is to be appended. LZ_OK or
 * LZ_ENOMEM. */
int lz_pedmd_grow(void **v, size_t *cap, size_t n, size_t size);

/* Start a window ending at t_end (absolute): what lz_pedmd_restore goes back to —
 * nothing saved yet, the system's scalars, the clock and the waiting messages as
 * they are now, an empty window log, no causality error. LZ_OK or LZ_ENOMEM.
 * O(waiting messages). */
int lz_pedmd_begin(lz_pedmd *r, double t_end);

/* The load of the busiest rank under cuts cut[0 .. P]: the most, over the ranks, of
 * the sum of load[] over the cells of its run of the curve. O(ncells). */
double lz_pedmd_busiest(const lz_pedmd_domains *d, const double *load, const uint32_t *cut);

/* Queue message m until the rank's clock reaches it. LZ_OK or LZ_ENOMEM. */
int lz_pedmd_wait(lz_pedmd *r, const lz_pedmd_message *m);

/* A prediction at t read cell c (HALO or BORDER): read[c] = t if later, the old stamp
 * kept the first time in a window (no memory: r->nomem). O(1). */
void lz_pedmd_read_at(lz_pedmd *r, uint32_t c, double t);

/* Every read stamp raised in this window back to what it was at its start. O(stamps). */
void lz_pedmd_unread(lz_pedmd *r);

/* 1 when every particle of cell c's block is at or before time t (relative): a
 * prediction at t can read them. O(block). */
int lz_pedmd_block_at(const lz_pedmd *r, uint32_t c, double t);

/* ---- local numbering (library, pedmd_slots.c) ---- */

/* The number of the particle in slot i of rank r (i itself when not compact). O(1). */
uint32_t lz_pedmd_id(const lz_pedmd *r, uint32_t i);

/* The slot of particle `id` on r, or -1 when r holds none for it. O(1) expected. */
int64_t lz_pedmd_slot(const lz_pedmd *r, uint32_t id);

/* The slot of particle `id` (< N) into *slot, made when r holds none: blank and ABSENT,
 * its count LZ_PEDMD_UNKNOWN (a rank meets a particle in a message, or as the partner
 * of an event in one). The rank's arrays may move (none of their addresses may be kept
 * across the call). LZ_OK, LZ_EDOM (id out of range) or LZ_ENOMEM. O(1) amortised. */
int lz_pedmd_hold(lz_pedmd *r, uint32_t id, uint32_t *slot);

/* Room for n slots (compact): when more than e->n, the system, the rank's arrays and
 * its index grow, the new slots blank (the window's snapshot of the system follows
 * them: a rollback restores its scalars, not its arrays). LZ_OK or LZ_ENOMEM. O(n). */
int lz_pedmd_reserve(lz_pedmd *r, size_t n);

/* A message as it travels: the particle and its event's partner by number. And one
 * that arrived, to this rank's slots (made by lz_pedmd_hold where needed). O(1). */
lz_pedmd_message lz_pedmd_outgoing(const lz_pedmd *r, uint32_t i, uint32_t kind, double t);
int lz_pedmd_incoming(lz_pedmd *r, lz_pedmd_message *m);

/* After a hand-over (lz_pedmd_take_end, its heap emptied, before its cells are filled):
 * keep the slots of the particles r holds and of the partners their events name, in
 * their order, drop the others, and when the room is more than half as much again
 * as that, give back all but an eighth more (compact only; else nothing). LZ_OK or
 * LZ_ENOMEM. O(slots). */
int lz_pedmd_compact(lz_pedmd *r);

/* The slots in use in the order of their particles' numbers (malloc'd, nslots of
 * them; the caller frees it). NULL with lz_error when out of memory. O(M log M). */
uint32_t *lz_pedmd_by_number(const lz_pedmd *r);

/* The particles of the whole system. O(1). */
size_t lz_pedmd_particles(const lz_pedmd *r);

/* A new rank's local numbering (compact): its system of e->n blank slots, none in use,
 * an empty index. LZ_OK or LZ_ENOMEM. O(e->n). */
int lz_pedmd_slots_init(lz_pedmd *r);

/* ---- the engine (library) ---- */

/* The decomposition of e's grid into P ranks along a curve, with even cuts (P <= the
 * cells). NULL with lz_error naming the range on a bad P or kind. O(ncells log). */
lz_pedmd_domains *lz_pedmd_domains_alloc(const lz_edmd *e, int P, int kind);
void lz_pedmd_domains_free(lz_pedmd_domains *d);


/* Rank `rank` of a run over d (kept, not owned) talking through msg, starting from the
 * serial system s (the same on every rank: lz_edmd_start done, rebase_auto = 0): it
 * keeps its owned particles and ghosts. NULL with lz_error. O(N + cells). */
lz_pedmd *lz_pedmd_alloc(const lz_edmd *s, const lz_pedmd_domains *d, lz_msg *msg,
                         const lz_pedmd_params *p);
/* The same, but the rank takes s itself as its own system rather than a copy (one
 * rank a process, as in lz-mpi: the process then holds one system, not two). s must
 * have cells and the binary heap, rebase_auto = 0 and sort_every = 0; it belongs to
 * the rank from then on (NULL with lz_error: then s is freed). O(N + cells). */
lz_pedmd *lz_pedmd_adopt(lz_edmd *s, const lz_pedmd_domains *d, lz_msg *msg,
                         const lz_pedmd_params *p);
/* Rank `rank` of a run over d in local numbering (p->compact = 1), holding nothing
 * yet: its box, cells and clock those of `shape` (a system whose scalars only are read:
 * its arrays may be absent, as on a process that never held the start). It takes its
 * particles with lz_pedmd_take_begin, _part and _end, as at a move of the cuts, from
 * the process that holds the start (lz-mpi: rank 0), so that no other process holds
 * all N. NULL with lz_error. O(cells). */
lz_pedmd *lz_pedmd_open(const lz_edmd *shape, const lz_pedmd_domains *d, lz_msg *msg,
                        const lz_pedmd_params *p);
void lz_pedmd_free(lz_pedmd *r);
/* Free the rank but keep its system, and return it: all N records, owned ones up to
 * date (the frame into which lz-mpi gathers the run's picture). Compact: a new system
 * of N, the owned records at their numbers, the others zero (NULL with lz_error when
 * out of memory: the rank is freed all the same). O(1), compact O(N). */
lz_edmd *lz_pedmd_release(lz_pedmd *r);

/* One turn of the rank's work (lz_work_fn for the stub, or a loop under MPI): run
 * towards t_stop (absolute time) window by window. */
int lz_pedmd_work(lz_pedmd *r, double t_stop, lz_work *state);

/* The rank's system, counters and committed events (n records). */
const lz_edmd *lz_pedmd_system(const lz_pedmd *r);
lz_pedmd_counts lz_pedmd_counters(const lz_pedmd *r);
const lz_pedmd_record *lz_pedmd_log(const lz_pedmd *r, size_t *n);
/* The role of particle `id` (its number) on r: ABSENT when r holds no slot for it. */
int lz_pedmd_role(const lz_pedmd *r, uint32_t id);

/* ---- moving the cuts during a run (params.balance) ---- */

/* 1 when rank r waits at a cut where the cuts may move: between windows after a
 * commit (not a rerun of the rollback check), before t_stop, and params.balance
 * windows after the last look. Every rank of a run answers alike at the same cut
 * (the verdicts are common), so that all of them take part in what follows. O(1). */
int lz_pedmd_balance_due(const lz_pedmd *r, double t_stop);

/* This rank's share of the load since its last look, into delta[0 .. cells-1]: the
 * events its cells committed since then (the sum over the ranks is the whole run's);
 * the next look is params.balance windows on. LZ_OK or LZ_ENOMEM. O(cells). */
int lz_pedmd_load_since(lz_pedmd *r, double *delta);

/* The particles rank r owns, as messages (id, record, own event with its time; kind
 * MIGRATE), into out[] (room for N; NULL: only count them): its part of the serial
 * picture. Their number. O(N). */
size_t lz_pedmd_owned(const lz_pedmd *r, lz_pedmd_message *out);
/* ... in parts: at most `most` of them, from particle *from on, which then moves past
 * the last one looked at (N: all done). O(particles looked at). */
size_t lz_pedmd_owned_part(const lz_pedmd *r, uint32_t *from, lz_pedmd_message *out,
                           size_t most);

/* The particles of a start s (lz_edmd_start done), as lz_pedmd_owned_part lists a
 * rank's: at most `most` from particle *from on (which moves past them), each with
 * its record and its event at its key in s's heap — what an opened rank takes
 * (lz_pedmd_open). Their number. O(most). */
size_t lz_pedmd_start_part(const lz_edmd *s, uint32_t *from, lz_pedmd_message *out,
                           size_t most);

/* At a cut (phase BEGIN, nothing waiting): rank r takes its share, under the cuts now
 * in r->d, of the serial picture that all[0 .. n-1] make — every particle once, from
 * lz_pedmd_owned of all ranks — as lz_pedmd_alloc would from a serial system, so that
 * the run goes on bit for bit (balances + 1): the records of the particles in its
 * cells and halo (every other one's count LZ_PEDMD_UNKNOWN), their roles and events,
 * the cells (each list in the order of the numbers) and the heap. In place: no second system.
 * LZ_OK; LZ_EINVAL (r unchanged) when not at a cut or when all[] is not every particle
 * once. O(N + cells). */
int lz_pedmd_take(lz_pedmd *r, const lz_pedmd_message *all, size_t n);

/* The same in parts, for a picture that comes in shares (lz-mpi): between windows, with
 * the new cuts in r->d, lz_pedmd_take_begin forgets what the rank held (LZ_OK or
 * LZ_EINVAL, as lz_pedmd_take); lz_pedmd_take_share lists, from *from on, at most
 * `most` of the particles the rank owned under the old cuts, as lz_pedmd_owned_part
 * (what it must send: to the owner of each one's cell under the new cuts and to the
 * ranks that hold that cell as HALO; their number); lz_pedmd_take_part takes n of the
 * particles sent to it — those in its cells and halo; others are skipped — LZ_OK, or
 * LZ_EINVAL when one comes twice or is not in the system (the rank is then half
 * taken: the run cannot go on); lz_pedmd_take_end gives every particle that did not
 * come the record count LZ_PEDMD_UNKNOWN, files the cells by number and fills the
 * heap (and counts a balance, unless no window has begun: an opened rank's set-up,
 * lz_pedmd_open). That every particle came to its new owner is the caller's check (the owned
 * particles of all ranks add up to N). LZ_OK, or LZ_ENOMEM from _end. O(N + cells)
 * in all, and 4 bytes a formerly owned particle until the end. */
int lz_pedmd_take_begin(lz_pedmd *r);
size_t lz_pedmd_take_share(const lz_pedmd *r, size_t *from, lz_pedmd_message *out,
                           size_t most);
int lz_pedmd_take_part(lz_pedmd *r, const lz_pedmd_message *m, size_t n);
int lz_pedmd_take_end(lz_pedmd *r);

/* Move the cuts of P ranks in one process: every rank between windows at the same
 * time T, nothing waiting; d->cut becomes cut[0 .. P] and every rank takes its share
 * of the picture their owned particles make (lz_pedmd_take). LZ_OK, LZ_EINVAL when not
 * at a cut, or LZ_ENOMEM. O(P (N + cells)). */
int lz_pedmd_recut(lz_pedmd *const *ranks, int P, lz_pedmd_domains *d, const uint32_t *cut);

/* The invariants of rank r at a cut: its owned particles lie in owned cells, each in
 * the heap once with its event, its ghosts in HALO cells; ghost records equal their
 * owners' (ranks[], all P of them, in one process: the stub). LZ_OK or LZ_EDOM naming
 * the first broken one. O(N). */
int lz_pedmd_audit(lz_pedmd *const *ranks, int P);

/* ---- a whole run in one process (the stub back-end) ---- */

/* P ranks of a run over the stub, made from one serial system. */
typedef struct {
	int P;
	lz_pedmd_domains *d;
	lz_stub *stub;
	lz_pedmd **rank;     /* rank[0 .. P-1] */
	int audit;           /* 1: lz_pedmd_audit at every cut (O(N P) each) */
	uint64_t most;       /* > 0: the run fails (LZ_EDOM, "no progress") once the ranks
	                        have processed more events than this, rolled back ones
	                        included: a livelock ends in a message, not a time-out */
	uint64_t audits;     /* cuts audited so far */
	double t_stop;       /* of the current lz_pedmd_sim_run */
	double audited_T;    /* the window start audited last */
} lz_pedmd_sim;

/* The ranks of a run of system s (lz_edmd_start done, rebase_auto = 0) along curve
 * `kind`, sp->ranks of them, talking through a stub with parameters sp. NULL with
 * lz_error on a bad parameter (naming its range) or no memory. O(P (N + cells)). */
lz_pedmd_sim *lz_pedmd_sim_alloc(const lz_edmd *s, int kind, const lz_stub_params *sp,
                                 const lz_pedmd_params *pp);
/* The same with the cuts cut[0 .. P] (0 = cut[0] < ... < cut[P] = the cells; NULL:
 * even cuts), e.g. from lz_pedmd_rebalance of a pilot run's load. */
lz_pedmd_sim *lz_pedmd_sim_alloc_cut(const lz_edmd *s, int kind, const uint32_t *cut,
                                     const lz_stub_params *sp, const lz_pedmd_params *pp);
void lz_pedmd_sim_free(lz_pedmd_sim *x);

/* Run every rank to t_stop (absolute, later than where they are): LZ_OK, the first
 * error of a rank, or LZ_EDOM from the audit (when asked) or a deadlock. */
int lz_pedmd_sim_run(lz_pedmd_sim *x, double t_stop);

/* The owned particles of every rank, written into out (a system of the same N and
 * grid; its cells are not updated): the serial picture of the run. */
void lz_pedmd_sim_gather(const lz_pedmd_sim *x, lz_edmd *out);

/* The serial reference of a parallel run: run e (rebase_auto = 0) to t_stop
 * (absolute), re-based at the multiples of `rebase` as the ranks are, so that both
 * round alike. LZ_OK or lz_edmd_run's error. O(events log N). */
int lz_pedmd_serial(lz_edmd *e, double t_stop, double rebase);

/* The committed events of every cell, all ranks together, into load[0 .. cells-1]. */
void lz_pedmd_sim_load(const lz_pedmd_sim *x, double *load);

/* The counters of all ranks summed (saved_bytes: the largest). */
lz_pedmd_counts lz_pedmd_sim_counts(const lz_pedmd_sim *x);
/* ... one rank's counters c added into s, as above: the events, kinds, late messages
 * and virial summed, saved_bytes the largest, and the protocol's own counts (windows,
 * rollbacks, conservative steps, balances: the same on every rank) taken from c. For
 * the counters of ranks in other processes (lz-mpi). O(1). */
void lz_pedmd_counts_add(lz_pedmd_counts *s, const lz_pedmd_counts *c);

/* Every rank's committed events in one array (malloc'd, the caller frees it), sorted
 * by time, then i, j and kind (lz_pedmd_record_order): the serial run's event log,
 * sorted alike, when params.log was 1. NULL with *n = 0 when there are none or no
 * memory. */
int lz_pedmd_record_order(const void *a, const void *b);
lz_pedmd_record *lz_pedmd_sim_log(const lz_pedmd_sim *x, size_t *n);

#endif
