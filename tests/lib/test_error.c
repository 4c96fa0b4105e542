/* test_error.c — status codes, messages, handlers, LZ_TODO. */
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lztest.h"
#include "support.h"

static int seen_code;
static char seen_message[256];

static void remember(int code, const char *message)
{
	seen_code = code;
	snprintf(seen_message, sizeof seen_message, "%s", message);
}

LZ_TEST(error_returns_code_and_keeps_message)
{
	lz_set_error_handler(remember);
	int rc = lz_error(LZ_EINVAL, "dt = %g must be > 0", -0.1);
	ck_assert_msg(rc == LZ_EINVAL, "lz_error returned %d, not the code it was given (%d)",
	              rc, LZ_EINVAL);
	ck_assert_msg(strcmp(lz_error_message(), "dt = -0.1 must be > 0") == 0,
	              "lz_error_message() is '%s', expected the formatted message",
	              lz_error_message());
	ck_assert_msg(seen_code == LZ_EINVAL && strcmp(seen_message, "dt = -0.1 must be > 0") == 0,
	              "the handler got code %d and '%s'", seen_code, seen_message);
}
END_TEST

LZ_TEST(error_handler_install_and_restore)
{
	lz_error_handler *runner = lz_set_error_handler(remember);
	ck_assert_msg(runner != NULL && runner != remember, "the runner's recording handler "
	              "should have been the previous one");
	ck_assert_msg(lz_set_error_handler(NULL) == remember,
	              "lz_set_error_handler did not return the handler it replaced");
	/* The default prints "lz: message" on stderr: catch it in a pipe. */
	int fds[2];
	ck_assert(pipe(fds) == 0);
	int saved = dup(STDERR_FILENO);
	dup2(fds[1], STDERR_FILENO);
	lz_error(LZ_EIO, "disk %s", "full");
	fflush(stderr);
	dup2(saved, STDERR_FILENO);
	close(fds[1]);
	char buf[128] = "";
	ssize_t n = read(fds[0], buf, sizeof buf - 1);
	buf[n > 0 ? n : 0] = '\0';
	ck_assert_msg(strcmp(buf, "lz: disk full\n") == 0,
	              "the default handler printed '%s', expected 'lz: disk full\\n'", buf);
}
END_TEST

LZ_TEST(error_long_message_is_truncated_safely)
{
	char big[10000];
	memset(big, 'x', sizeof big - 1);
	big[sizeof big - 1] = '\0';
	lz_error(LZ_EINVAL, "%s%s", big, big);
	size_t n = strlen(lz_error_message());
	ck_assert_msg(n > 1000 && n < sizeof big,
	              "a 20000-character message should be cut to the buffer, got %zu chars", n);
}
END_TEST

static void *other_thread(void *arg)
{
	lz_error(LZ_EDOM, "from the other thread");
	return NULL;
}

LZ_TEST(error_message_is_per_thread)
{
	lz_error(LZ_EINVAL, "from the main thread");
	pthread_t t;
	ck_assert(pthread_create(&t, NULL, other_thread, NULL) == 0);
	pthread_join(t, NULL);
	ck_assert_msg(strcmp(lz_error_message(), "from the main thread") == 0,
	              "another thread's error replaced this thread's message: '%s'",
	              lz_error_message());
}
END_TEST

LZ_TEST(error_strerror_names_every_code)
{
	int codes[] = {LZ_OK, LZ_EINVAL, LZ_ENOMEM, LZ_EDOM, LZ_EIO, LZ_EPHYS, LZ_ESYNTAX};
	for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++)
		for (size_t k = 0; k < i; k++)
			ck_assert_msg(strcmp(lz_strerror(codes[i]), lz_strerror(codes[k])) != 0,
			              "codes %d and %d have the same name '%s'", codes[i], codes[k],
			              lz_strerror(codes[i]));
	ck_assert_msg(strcmp(lz_strerror(LZ_EINVAL), "invalid argument") == 0,
	              "LZ_EINVAL is '%s'", lz_strerror(LZ_EINVAL));
	ck_assert_msg(lz_strerror(12345) != NULL && *lz_strerror(12345),
	              "an unknown code should still have a name");
}
END_TEST

static void todo_to_pipe(const char *function, const char *file)
{
	dprintf(STDOUT_FILENO, "handler: %s in %s", function, file);
}

/* Run LZ_TODO() in a child with the given handler; returns what it wrote on fd 1 and
 * fd 2, and its wait status. */
static int run_todo(lz_todo_handler *h, char *out, size_t size)
{
	int fds[2];
	ck_assert(pipe(fds) == 0);
	pid_t pid = fork();
	ck_assert(pid >= 0);
	if (pid == 0) {
		dup2(fds[1], STDOUT_FILENO);
		dup2(fds[1], STDERR_FILENO);
		lz_set_todo_handler(h);
		LZ_TODO();
	}
	close(fds[1]);
	size_t len = 0;
	for (ssize_t n; (n = read(fds[0], out + len, size - 1 - len)) > 0;)
		len += (size_t)n;
	out[len] = '\0';
	close(fds[0]);
	int status;
	waitpid(pid, &status, 0);
	return status;
}

LZ_TEST(error_todo_reports_and_aborts)
{
	char out[512];
	int status = run_todo(NULL, out, sizeof out);
	ck_assert_msg(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT,
	              "LZ_TODO() must abort (SIGABRT) so a stub can never pass");
	ck_assert_msg(strstr(out, "not implemented: run_todo (") && strstr(out, "test_error.c)"),
	              "LZ_TODO() printed '%s', expected 'not implemented: run_todo (...test_error.c)'",
	              out);
	status = run_todo(todo_to_pipe, out, sizeof out);
	ck_assert_msg(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT,
	              "LZ_TODO() must abort after its handler returns");
	ck_assert_msg(strstr(out, "handler: run_todo in") != NULL,
	              "the todo handler was not called: the child wrote '%s'", out);
}
END_TEST
