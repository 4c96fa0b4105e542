/* bigmem.c — large arrays on transparent huge pages when the kernel offers them
 * (lz/bigmem.h). */
/* MADV_HUGEPAGE is a Linux extension, outside the X/Open set the build asks for */
#define _DEFAULT_SOURCE
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "lz/bigmem.h"

enum { HUGE_PAGE = 2 << 20, LINE = 64 };

void *lz_bigmem_alloc(size_t size)
{
	size_t align = size >= 2 * HUGE_PAGE ? HUGE_PAGE : LINE;
	size_t rounded = (size + align - 1) / align * align;
	void *p = aligned_alloc(align, rounded ? rounded : align);
#ifdef MADV_HUGEPAGE
	if (p && align == HUGE_PAGE)
		madvise(p, rounded, MADV_HUGEPAGE);  /* a hint: failure leaves small pages */
#endif
	return p;
}

void lz_bigmem_free(void *p) { free(p); }

void *lz_bigmem_resize(void *p, size_t old, size_t size)
{
	void *q = lz_bigmem_alloc(size);
	if (q && p)
		memcpy(q, p, old < size ? old : size);
	if (q)
		free(p);
	return q;
}

void *lz_bigmem_sparse(size_t size)
{
	void *p = mmap(NULL, size ? size : 1, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS,
	               -1, 0);
	if (p == MAP_FAILED)
		return NULL;
#ifdef MADV_HUGEPAGE
	if (size >= 2 * HUGE_PAGE)
		madvise(p, size, MADV_HUGEPAGE);
#endif
	return p;
}

void lz_bigmem_sparse_free(void *p, size_t size)
{
	if (p)
		munmap(p, size ? size : 1);
}
