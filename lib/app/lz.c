/* lz.c — the `lz` command; everything is in cli.c so that the tests can call it. */
#include "cli.h"

int main(int argc, char **argv)
{
	return lz_cli_main(argc, argv);
}
