/* output.c — data files, summary.json, run directories and gnuplot. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lz/error.h"
#include "lz/output.h"

/* ---- data files ---- */

struct lz_data {
	FILE *f;
	int ncol;
	char path[];  /* for the message when a write fails */
};

lz_data *lz_data_open(const char *path, const char *title, int ncol,
                      const char *const *names, const char *const *units)
{
	if (ncol < 1 || ncol > 64) {
		lz_error(LZ_EINVAL, "data file '%s': ncol = %d is out of range [1, 64]", path, ncol);
		return NULL;
	}
	for (int i = 0; i < ncol; i++)
		if (!names || !names[i] || !names[i][0]) {
			lz_error(LZ_EINVAL, "data file '%s': column %d has no name", path, i + 1);
			return NULL;
		}
	lz_data *d = malloc(sizeof *d + strlen(path) + 1);
	if (!d) {
		lz_error(LZ_ENOMEM, "no memory to open data file '%s'", path);
		return NULL;
	}
	strcpy(d->path, path);
	d->ncol = ncol;
	d->f = fopen(path, "w");
	if (!d->f) {
		lz_error(LZ_EIO, "cannot write data file '%s': %s", path, strerror(errno));
		free(d);
		return NULL;
	}
	if (title)
		fprintf(d->f, "# %s\n", title);
	fputc('#', d->f);
	for (int i = 0; i < ncol; i++) {
		const char *u = units ? units[i] : NULL;
		fprintf(d->f, "%s%s", i ? "  " : " ", names[i]);
		if (u && u[0])
			fprintf(d->f, " [%s]", u);
	}
	fputc('\n', d->f);
	return d;
}

/* printf would write "-nan" for some NaNs; gnuplot and readers expect nan, inf, -inf. */
static void data_value(FILE *f, double v)
{
	if (isnan(v))
		fputs("nan", f);
	else if (isinf(v))
		fputs(v > 0 ? "inf" : "-inf", f);
	else
		fprintf(f, "%.12g", v);
}

void lz_data_row(lz_data *d, const double *values)
{
	for (int i = 0; i < d->ncol; i++) {
		if (i)
			fputc(' ', d->f);
		data_value(d->f, values[i]);
	}
	fputc('\n', d->f);
}

void lz_data_comment(lz_data *d, const char *text)
{
	fprintf(d->f, "# %s\n", text);
}

int lz_data_close(lz_data *d)
{
	if (!d)
		return LZ_OK;
	int bad = ferror(d->f);
	bad |= fclose(d->f) != 0;
	int rc = bad ? lz_error(LZ_EIO, "writing data file '%s' failed (disk full?)", d->path)
	             : LZ_OK;
	free(d);
	return rc;
}

/* ---- summary.json ---- */

/* Keys are remembered by a 64-bit hash, so a key written twice — which would make the
 * object invalid JSON — is caught at lz_json_end. */
#define JSON_KEYS_MAX 512
struct lz_json {
	FILE *f;
	int own;  /* 1: lz_json_open made f, lz_json_end closes it */
	int n;    /* members written so far */
	uint64_t hash[JSON_KEYS_MAX];  /* of the first JSON_KEYS_MAX keys */
	char twice[128];               /* the first key written twice, or "" */
};

lz_json *lz_json_begin(FILE *f)
{
	lz_json *j = malloc(sizeof *j);
	if (!j) {
		lz_error(LZ_ENOMEM, "no memory for a JSON writer");
		return NULL;
	}
	j->f = f;
	j->own = 0;
	j->n = 0;
	j->twice[0] = '\0';
	fputc('{', f);
	return j;
}

lz_json *lz_json_open(const char *path)
{
	FILE *f = fopen(path, "w");
	if (!f) {
		lz_error(LZ_EIO, "cannot write '%s': %s", path, strerror(errno));
		return NULL;
	}
	lz_json *j = lz_json_begin(f);
	if (!j) {
		fclose(f);
		return NULL;
	}
	j->own = 1;
	return j;
}

/* A JSON string: quotes and backslashes escaped, control characters as \uXXXX.
 * Other bytes pass through: the text is UTF-8. */
static void json_string(FILE *f, const char *s, const char *suffix)
{
	fputc('"', f);
	for (int part = 0; part < 2; part++, s = suffix)
		for (const unsigned char *p = (const unsigned char *)s; p && *p; p++) {
			if (*p == '"' || *p == '\\')
				fprintf(f, "\\%c", *p);
			else if (*p < 0x20 || *p == 0x7f)
				fprintf(f, "\\u%04x", *p);
			else
				fputc(*p, f);
		}
	fputc('"', f);
}

/* FNV-1a of key followed by suffix. */
static uint64_t json_hash(const char *key, const char *suffix)
{
	uint64_t h = 14695981039346656037ULL;
	for (int part = 0; part < 2; part++, key = suffix)
		for (const unsigned char *p = (const unsigned char *)key; p && *p; p++)
			h = (h ^ *p) * 1099511628211ULL;
	return h;
}

static void json_remember(lz_json *j, const char *key, const char *suffix)
{
	uint64_t h = json_hash(key, suffix);
	int known = j->n < JSON_KEYS_MAX ? j->n : JSON_KEYS_MAX;
	for (int i = 0; i < known && !j->twice[0]; i++)
		if (j->hash[i] == h)
			snprintf(j->twice, sizeof j->twice, "%s%s", key, suffix ? suffix : "");
	if (j->n < JSON_KEYS_MAX)
		j->hash[j->n] = h;
}

/* Start the member `key suffix`: separator, name, colon. */
static void json_key(lz_json *j, const char *key, const char *suffix)
{
	json_remember(j, key, suffix);
	fputs(j->n++ ? ",\n  " : "\n  ", j->f);
	json_string(j->f, key, suffix);
	fputs(": ", j->f);
}

static void json_number(FILE *f, double v)
{
	if (isfinite(v))
		fprintf(f, "%.17g", v);
	else
		fputs("null", f);
}

void lz_json_num(lz_json *j, const char *key, double v)
{
	json_key(j, key, NULL);
	json_number(j->f, v);
}

void lz_json_int(lz_json *j, const char *key, long long v)
{
	json_key(j, key, NULL);
	fprintf(j->f, "%lld", v);
}

void lz_json_str(lz_json *j, const char *key, const char *v)
{
	json_key(j, key, NULL);
	json_string(j->f, v, NULL);
}

void lz_json_bool(lz_json *j, const char *key, int v)
{
	json_key(j, key, NULL);
	fputs(v ? "true" : "false", j->f);
}

void lz_json_err(lz_json *j, const char *key, double v, double err)
{
	lz_json_num(j, key, v);
	json_key(j, key, "_err");
	json_number(j->f, err);
}

int lz_json_end(lz_json *j)
{
	if (!j)
		return LZ_OK;
	fputs(j->n ? "\n}\n" : "}\n", j->f);
	int bad = fflush(j->f) != 0 || ferror(j->f);
	if (j->own)
		bad |= fclose(j->f) != 0;
	char twice[sizeof j->twice];
	snprintf(twice, sizeof twice, "%s", j->twice);
	free(j);
	if (bad)
		return lz_error(LZ_EIO, "writing a JSON summary failed (disk full?)");
	if (twice[0])
		return lz_error(LZ_EINVAL, "the summary key '%s' was written twice (a JSON object "
		                "needs unique keys)", twice);
	return LZ_OK;
}

/* ---- run directories ---- */

/* Whether `path` may be replaced by a run: absent, an empty directory, or a directory
 * with a summary.json (a run's). Anything else may be a user's own directory (--out ~
 * is one typo away), and lz never deletes those. */
static int rundir_replaceable(const char *path, int *exists)
{
	struct stat st;
	*exists = 0;
	if (lstat(path, &st) != 0) {
		if (errno == ENOENT)
			return LZ_OK;
		return lz_error(LZ_EIO, "cannot inspect output directory '%s': %s", path,
		                strerror(errno));
	}
	*exists = 1;
	if (!S_ISDIR(st.st_mode))
		return lz_error(LZ_EINVAL, "output directory '%s' exists and is not a directory; "
		                "choose another --out", path);
	DIR *dir = opendir(path);
	if (!dir)
		return lz_error(LZ_EIO, "cannot read output directory '%s': %s", path,
		                strerror(errno));
	int entries = 0, summary = 0;
	for (struct dirent *e; (e = readdir(dir));) {
		if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
			continue;
		entries++;
		summary |= strcmp(e->d_name, "summary.json") == 0;
	}
	closedir(dir);
	if (entries && !summary)
		return lz_error(LZ_EINVAL, "output directory '%s' exists and is not a run "
		                "directory (it has no summary.json): lz will not replace it; "
		                "choose another --out or remove it yourself", path);
	return LZ_OK;
}

/* mkdir -p of the directories above `path`; one that exists must be a directory. */
static int mkdir_parents(const char *path)
{
	char buf[sizeof ((lz_rundir *)0)->final];
	struct stat st;
	snprintf(buf, sizeof buf, "%s", path);
	for (char *p = buf + 1; (p = strchr(p, '/')); p++) {
		*p = '\0';
		if (mkdir(buf, 0777) != 0 && errno != EEXIST)
			return lz_error(LZ_EIO, "cannot create directory '%s': %s", buf,
			                strerror(errno));
		if (stat(buf, &st) != 0 || !S_ISDIR(st.st_mode))
			return lz_error(LZ_EIO, "cannot create a directory in '%s': it is not a "
			                "directory", buf);
		*p = '/';
	}
	return LZ_OK;
}

int lz_rundir_begin(lz_rundir *d, const char *out)
{
	d->final[0] = d->tmp[0] = '\0';
	size_t n = out ? strlen(out) : 0;
	if (n == 0)
		return lz_error(LZ_EINVAL, "the output directory name is empty");
	while (n > 1 && out[n - 1] == '/')  /* "runs/x/" is runs/x, not runs/x/.partial */
		n--;
	if (n >= sizeof d->final)
		return lz_error(LZ_EINVAL, "output directory name is too long (%zu bytes)", n);
	memcpy(d->final, out, n);
	d->final[n] = '\0';
	const char *base = strrchr(d->final, '/');
	base = base ? base + 1 : d->final;
	if (!*base || strcmp(base, ".") == 0 || strcmp(base, "..") == 0)
		return lz_error(LZ_EINVAL, "output directory '%s' must name a directory of its "
		                "own (not /, . or ..)", out);
	int exists, rc = rundir_replaceable(d->final, &exists);
	if (rc != LZ_OK)
		return rc;
	int len = snprintf(d->tmp, sizeof d->tmp, "%s.partial-%ld", d->final, (long)getpid());
	if (len < 0 || (size_t)len >= sizeof d->tmp) {
		d->tmp[0] = '\0';
		return lz_error(LZ_EINVAL, "output directory name '%s' is too long", out);
	}
	/* A directory of that name is left over from a crashed run whose pid we reuse. */
	if ((rc = mkdir_parents(d->final)) != LZ_OK || (rc = lz_rmtree(d->tmp)) != LZ_OK) {
		d->tmp[0] = '\0';
		return rc;
	}
	if (mkdir(d->tmp, 0777) != 0) {
		rc = lz_error(LZ_EIO, "cannot create run directory '%s': %s", d->tmp,
		              strerror(errno));
		d->tmp[0] = '\0';
		return rc;
	}
	return LZ_OK;
}

int lz_rundir_file(const lz_rundir *d, const char *name, char *buf, size_t size)
{
	int len = snprintf(buf, size, "%s/%s", d->tmp, name);
	if (len < 0 || (size_t)len >= size)
		return lz_error(LZ_EINVAL, "path '%s/%s' does not fit in %zu bytes", d->tmp, name,
		                size);
	return LZ_OK;
}

/* The old run is moved aside before the new one takes its name, so that at every
 * moment one complete run directory exists. */
int lz_rundir_commit(lz_rundir *d)
{
	if (!d->tmp[0])
		return lz_error(LZ_EINVAL, "no run directory to commit (begin failed or already "
		                "committed)");
	int exists, rc = rundir_replaceable(d->final, &exists);
	if (rc != LZ_OK)
		return rc;
	char old[sizeof d->final + 32];
	snprintf(old, sizeof old, "%s.old-%ld", d->final, (long)getpid());
	if (exists && ((rc = lz_rmtree(old)) != LZ_OK))
		return rc;
	if (exists && rename(d->final, old) != 0)
		return lz_error(LZ_EIO, "cannot move the old run '%s' aside: %s", d->final,
		                strerror(errno));
	if (rename(d->tmp, d->final) != 0) {
		rc = lz_error(LZ_EIO, "cannot rename '%s' to '%s': %s", d->tmp, d->final,
		              strerror(errno));
		if (exists)
			rename(old, d->final);
		return rc;
	}
	d->tmp[0] = '\0';
	return exists ? lz_rmtree(old) : LZ_OK;
}

void lz_rundir_abort(lz_rundir *d)
{
	if (d->tmp[0])
		lz_rmtree(d->tmp);
	d->tmp[0] = '\0';
}

/* nftw callback: remove one entry; a non-zero return (errno) stops the walk. */
static int rmtree_entry(const char *path, const struct stat *st, int flag,
                           struct FTW *ftw)
{
	return remove(path) == 0 ? 0 : errno ? errno : EIO;
}

int lz_rmtree(const char *path)
{
	struct stat st;
	if (lstat(path, &st) != 0)
		return errno == ENOENT ? LZ_OK
		       : lz_error(LZ_EIO, "cannot remove '%s': %s", path, strerror(errno));
	/* Children first (FTW_DEPTH); symbolic links removed, never followed (FTW_PHYS);
	 * nothing on another file system (FTW_MOUNT). */
	int rc = nftw(path, rmtree_entry, 16, FTW_DEPTH | FTW_PHYS | FTW_MOUNT);
	if (rc != 0)
		return lz_error(LZ_EIO, "cannot remove '%s' (or something in it): %s", path,
		                strerror(rc > 0 ? rc : errno));
	return LZ_OK;
}

/* ---- gnuplot ---- */

/* gnuplot's complaint, on one line: newlines and runs of spaces squeezed. */
static void squeeze(char *s)
{
	char *w = s;
	for (const char *r = s; *r; r++) {
		int space = *r == ' ' || *r == '\n' || *r == '\t' || *r == '\r';
		if (space && (w == s || w[-1] == ' '))
			continue;
		*w++ = space ? ' ' : *r;
	}
	while (w > s && w[-1] == ' ')
		w--;
	*w = '\0';
}

/* Exit statuses of the child before gnuplot runs: as a shell reports them. */
enum { LZ_CHILD_NO_DIR = 126, LZ_CHILD_NO_EXEC = 127 };

static void gnuplot_child(const char *dir, const char *script, int err)
{
	int null = open("/dev/null", O_RDWR);
	if (null >= 0) {
		dup2(null, STDIN_FILENO);
		dup2(null, STDOUT_FILENO);
	}
	dup2(err, STDERR_FILENO);
	if (chdir(dir) != 0)
		_exit(LZ_CHILD_NO_DIR);
	execlp("gnuplot", "gnuplot", script, (char *)NULL);
	_exit(LZ_CHILD_NO_EXEC);
}

int lz_gnuplot(const char *dir, const char *script)
{
	int pipefd[2];
	if (pipe(pipefd) != 0)
		return lz_error(LZ_EIO, "cannot run gnuplot: pipe: %s", strerror(errno));
	pid_t pid = fork();
	if (pid < 0) {
		close(pipefd[0]);
		close(pipefd[1]);
		return lz_error(LZ_EIO, "cannot run gnuplot: fork: %s", strerror(errno));
	}
	if (pid == 0) {
		close(pipefd[0]);
		gnuplot_child(dir, script, pipefd[1]);
	}
	close(pipefd[1]);
	/* Keep the start of gnuplot's stderr for the message; drain the rest. */
	char msg[512], sink[512];
	size_t len = 0;
	for (;;) {
		int room = len < sizeof msg - 1;
		ssize_t got = read(pipefd[0], room ? msg + len : sink,
		                   room ? sizeof msg - 1 - len : sizeof sink);
		if (got < 0 && errno == EINTR)
			continue;
		if (got <= 0)
			break;
		len += room ? (size_t)got : 0;
	}
	msg[len] = '\0';
	close(pipefd[0]);
	int status;
	while (waitpid(pid, &status, 0) < 0)
		if (errno != EINTR)
			return lz_error(LZ_EIO, "gnuplot: waitpid: %s", strerror(errno));
	if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
		return LZ_OK;
	if (WIFEXITED(status) && WEXITSTATUS(status) == LZ_CHILD_NO_EXEC)
		return 1;
	if (WIFEXITED(status) && WEXITSTATUS(status) == LZ_CHILD_NO_DIR)
		return lz_error(LZ_EIO, "gnuplot: cannot enter directory '%s'", dir);
	squeeze(msg);
	return lz_error(LZ_EIO, "gnuplot %s (in %s) failed (%s %d): %s", script, dir,
	                WIFEXITED(status) ? "exit status" : "signal",
	                WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status),
	                msg[0] ? msg : "no message");
}
