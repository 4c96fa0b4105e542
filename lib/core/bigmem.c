/* bigmem.c — large arrays on transparent huge pages when the kernel offers them
 * (lz/bigmem.h). */
/* MADV_HUGEPAGE is a Linux extension, outside the X/Open set the build asks for */
#define _DEFAULT_SOURCE
#include <stdlib.h>
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
