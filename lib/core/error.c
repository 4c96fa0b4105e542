/* error.c — status codes, the last message of each thread, and the handlers. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/error.h"

/* Long enough for a message that lists every key of a method. */
#define MESSAGE_MAX 2048

static _Thread_local char last_message[MESSAGE_MAX];
static lz_error_handler *error_handler;  /* NULL: the default, print on stderr */
static lz_todo_handler *todo_handler;    /* NULL: print on stderr */

static void error_default(int code, const char *message)
{
	fprintf(stderr, "lz: %s\n", message);
}

int lz_error(int code, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(last_message, sizeof last_message, fmt, ap);
	va_end(ap);
	(error_handler ? error_handler : error_default)(code, last_message);
	return code;
}

const char *lz_error_message(void)
{
	return last_message;
}

lz_error_handler *lz_set_error_handler(lz_error_handler *h)
{
	lz_error_handler *old = error_handler ? error_handler : error_default;
	error_handler = h;
	return old;
}

void lz_error_quiet(int code, const char *message)
{
}

const char *lz_strerror(int code)
{
	switch (code) {
	case LZ_OK:      return "success";
	case LZ_EINVAL:  return "invalid argument";
	case LZ_ENOMEM:  return "out of memory";
	case LZ_EDOM:    return "outside the domain";
	case LZ_EIO:     return "input/output error";
	case LZ_EPHYS:   return "physics guard tripped";
	case LZ_ESYNTAX: return "syntax error";
	default:         return "unknown error code";
	}
}

void lz_set_todo_handler(lz_todo_handler *h)
{
	todo_handler = h;
}

_Noreturn void lz_todo(const char *function, const char *file)
{
	if (todo_handler)
		todo_handler(function, file);
	else
		fprintf(stderr, "not implemented: %s (%s)\n", function, file);
	abort();
}
