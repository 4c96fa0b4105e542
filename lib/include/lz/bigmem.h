/* lz/bigmem.h — allocation of large arrays that are read at random (event-driven
 * particle and heap arrays of 10^6 particles and more).
 *
 * Reading a few bytes at random addresses from 100 MB costs, besides the cache miss,
 * a miss of the address translation (TLB): with 4 kB pages the processor can keep the
 * translations of only a few MB. Linux's transparent huge pages (2 MB) cover 512 times
 * as much per entry; where the kernel hands them out only on request ("madvise" in
 * /sys/kernel/mm/transparent_hugepage/enabled), lz_bigmem_alloc asks for them. The
 * request is a hint: without huge pages the memory is ordinary. Small arrays are
 * plain 64-byte aligned allocations.
 */
#ifndef LZ_BIGMEM_H
#define LZ_BIGMEM_H

#include <stddef.h>

/* size bytes, aligned to 64 bytes (to 2 MB and advised huge pages from 4 MB up);
 * uninitialised; NULL when out of memory (no lz_error: the caller names what it
 * was for). Free with lz_bigmem_free. O(1). */
void *lz_bigmem_alloc(size_t size);
void lz_bigmem_free(void *p);

/* size bytes of zeros in pages of their own (an anonymous mapping; huge pages advised
 * from 4 MB up): a page takes memory only once a byte of it is written, so a process
 * that writes a part of the array holds that part — a rank's share of the cells
 * (lz/pedmd.h). NULL when out of address space. Free with lz_bigmem_sparse_free and
 * the same size. O(1). */
void *lz_bigmem_sparse(size_t size);
void lz_bigmem_sparse_free(void *p, size_t size);

/* A block of `size` bytes (as lz_bigmem_alloc) holding the first min(old, size) bytes
 * of p, which it replaces (p freed); NULL when out of memory, and then p is kept as it
 * was. O(size). */
void *lz_bigmem_resize(void *p, size_t old, size_t size);

#endif
