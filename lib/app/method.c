/* method.c — the registry of engines, in course order (a stage adds its method here),
 * and the binding of a scene to one. */
#include <string.h>

#include "lz/error.h"
#include "method.h"

static const lz_method *const lz_registry[] = {
	&lz_method_verlet,
	&lz_method_walk,
	&lz_method_lattice_gas,
	&lz_method_field,
	&lz_method_nlist,
	&lz_method_edmd,
	&lz_method_pedmd,
};

const lz_method *lz_method_find(const char *name)
{
	for (size_t i = 0; name && i < sizeof lz_registry / sizeof lz_registry[0]; i++)
		if (strcmp(lz_registry[i]->name, name) == 0)
			return lz_registry[i];
	return NULL;
}

const lz_method *const *lz_methods(size_t *n)
{
	*n = sizeof lz_registry / sizeof lz_registry[0];
	return lz_registry;
}

int lz_method_bind(const lz_method *m, lz_scene *s)
{
	int rc = lz_scene_bind(s, &m->keys);
	if (rc == LZ_OK && m->check && (rc = m->check(s)) != LZ_OK)
		lz_scene_unbind(s);
	return rc;
}
