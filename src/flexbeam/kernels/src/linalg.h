/* Small dense linear algebra with a fixed order of operations (linalg.c).
 *
 * numpy's @, dot and linalg call the BLAS/LAPACK kernel that OpenBLAS picks for the CPU (and MKL or another
 * library elsewhere), whose sums run in a CPU-dependent order: the same matrices give results that differ in the
 * last bits from machine to machine.  These routines sum in one documented order, without contraction, so their
 * results are a function of their arguments alone.  All matrices are row-major, C-contiguous.  The sizes here are
 * those of a modal model (tens of modes, a quadrature of hundreds of points), where plain loops are fast enough.
 */
#ifndef FLEXBEAM_LINALG_H
#define FLEXBEAM_LINALG_H

/* C (m x n) = A (m x k) B (k x n); each entry summed over k in increasing order. */
void fb_la_matmul(const double *A, const double *B, double *C, int m, int k, int n);
/* C (ka x kb) = A^T diag(w) B for A (m x ka), B (m x kb): a quadrature sum over the m rows in increasing order. */
void fb_la_gram(const double *A, const double *w, const double *B, double *C, int m, int ka, int kb);
/* X = A^-1 B for A (n x n), B (n x nrhs): LU with partial pivoting (A and B overwritten, X in B); -1 if singular. */
int fb_la_solve(double *A, double *B, int n, int nrhs);
/* L (lower, in A) with A = L L^T; -1 if A is not positive definite. */
int fb_la_cholesky(double *A, int n);
/* Eigenvalues w (ascending) and orthonormal eigenvectors V (columns) of the symmetric A (n x n) by the cyclic
 * Jacobi method (A overwritten); each eigenvector's largest-magnitude component (the first of equal ones) is made
 * positive.  Returns the sweeps used, -1 if not converged. */
int fb_la_eigh(double *A, int n, double *w, double *V);

#endif
