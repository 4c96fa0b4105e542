/* cli.h — the `lz` command line, callable in-process (the tests call it).
 *
 *   lz run SCENE [key=value ...] [--out DIR] [--quiet]
 *   lz list
 *   lz help [METHOD]
 *
 * SCENE is a path or the name of a scene in the scene directory (datasets/scenes,
 * or $LZ_SCENES). A run prints `lz: results in DIR/` on stderr and the table of its
 * results on stdout (run_table.h), nothing with --quiet; `lz help` says how the
 * command line overrides the scene. Exit status: 0 success, 1 the run failed (a
 * physics guard or an I/O error), 2 bad input (usage, scene file, key, value, an
 * --out that cannot be made) — with a one-line message on stderr, and no output
 * directory left behind; a run ended by SIGINT, SIGTERM or SIGHUP removes its partial
 * directory and ends by that signal (interrupt.h).
 */
#ifndef LZ_CLI_H
#define LZ_CLI_H

int lz_cli_main(int argc, char **argv);

/* The directory scenes are looked up in. */
const char *lz_scene_dir(void);

#endif
