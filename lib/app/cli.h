/* cli.h — the `lz` command line, callable in-process (the tests call it).
 *
 *   lz run SCENE [key=value ...] [--out DIR] [--quiet]
 *   lz list
 *   lz help [METHOD]
 *
 * SCENE is a path or the name of a scene in the scene directory (datasets/scenes,
 * or $LZ_SCENES). Exit status: 0 success, 1 the run failed (a physics guard or an
 * I/O error), 2 bad input (usage, scene file, key, value) — with a one-line message
 * on stderr, and no output directory left behind.
 */
#ifndef LZ_CLI_H
#define LZ_CLI_H

int lz_cli_main(int argc, char **argv);

/* The directory scenes are looked up in. */
const char *lz_scene_dir(void);

#endif
