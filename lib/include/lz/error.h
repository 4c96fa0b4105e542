/* lz/error.h — status codes and error reporting for the whole library.
 *
 * A function that can fail returns an int status: LZ_OK (0) or one of the codes
 * below. Before returning a code it calls lz_error(), whose message names the bad
 * value and what was allowed ("dt = -0.1 must be > 0"). The library never exits
 * and never aborts, except LZ_TODO() in an assignment stub.
 */
#ifndef LZ_ERROR_H
#define LZ_ERROR_H

enum {
	LZ_OK = 0,
	LZ_EINVAL = 2,  /* an argument or scene value is invalid or out of range */
	LZ_ENOMEM = 3,  /* allocation failed */
	LZ_EDOM = 4,    /* the mathematics is undefined here (e.g. no stable root) */
	LZ_EIO = 5,     /* a file could not be read or written */
	LZ_EPHYS = 6,   /* a physics guard tripped (overlap, energy blow-up, NaN) */
	LZ_ESYNTAX = 7  /* a scene or data file is malformed */
};

/* Called with the code and the formatted message of every lz_error(). */
typedef void lz_error_handler(int code, const char *message);

/* Format a message (printf-style), remember it (lz_error_message) and pass it to the
 * current handler. Returns code, so a caller can write `return lz_error(...)`. */
int lz_error(int code, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The message of the most recent lz_error() in this thread ("" if none). */
const char *lz_error_message(void);

/* Install a handler; NULL restores the default, which prints "lz: message" on stderr.
 * Returns the previous handler. lz_error_quiet is a handler that prints nothing. */
lz_error_handler *lz_set_error_handler(lz_error_handler *h);
void lz_error_quiet(int code, const char *message);

/* A short name for a status code: "invalid argument", ... */
const char *lz_strerror(int code);

/* Assignment stubs call LZ_TODO(): it reports "not implemented: FUNCTION (FILE)"
 * through the todo handler (the test runner turns it into a test failure), then
 * aborts. */
#define LZ_TODO() lz_todo(__func__, __FILE__)
_Noreturn void lz_todo(const char *function, const char *file);
typedef void lz_todo_handler(const char *function, const char *file);
void lz_set_todo_handler(lz_todo_handler *h);

#endif
