/* fpsum_lib.c — the two reference summations the graded ones are measured against. */
#include "lz/fpsum.h"

double lz_sum_naive(const double *x, size_t n)
{
	double s = 0.0;
	for (size_t i = 0; i < n; i++)
		s += x[i];
	return s;
}

double lz_sum_kahan(const double *x, size_t n)
{
	lz_kahan k = {0};
	for (size_t i = 0; i < n; i++)
		lz_kahan_add(&k, x[i]);
	return lz_kahan_value(&k);
}
