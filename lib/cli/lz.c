/* lz.c — the `lz` command; everything is in lib/src/cli.c so that tests can call it. */
#include "lz/cli.h"

int main(int argc, char **argv)
{
	return lz_cli_main(argc, argv);
}
