/* The MPI and METIS calls of verbss-mpi behind plain C types, so that the
 * Rust side (src/sys.rs) needs no bindings generator and no knowledge of
 * the MPI implementation's handle types or METIS's index width.
 *
 * Communicators travel as Fortran handles (MPI_Fint, converted with
 * MPI_Comm_f2c on each call); element types as the codes of `Scalar::CODE`
 * in src/sys.rs. Every function returns the MPI or METIS status. build.rs
 * compiles this file only when it has found MPI and METIS. */

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <metis.h>
#include <mpi.h>

_Static_assert(sizeof(MPI_Fint) == sizeof(int), "MPI_Fint is not an int");

/* The MPI type of a `Scalar::CODE`. */
static MPI_Datatype datatype(int code) {
    switch (code) {
    case 0:
        return MPI_UINT8_T;
    case 1:
        return MPI_INT32_T;
    case 2:
        return MPI_UINT32_T;
    case 3:
        return MPI_UINT64_T;
    default:
        return MPI_DOUBLE;
    }
}

int verbss_mpi_init(void) {
    int provided;
    return MPI_Init_thread(NULL, NULL, MPI_THREAD_SINGLE, &provided);
}

int verbss_mpi_finalize(void) { return MPI_Finalize(); }

/* 1 once MPI is initialised, plus 2 once it is finalised. */
int verbss_mpi_state(void) {
    int initialized = 0, finalized = 0;
    MPI_Initialized(&initialized);
    MPI_Finalized(&finalized);
    return (initialized ? 1 : 0) + (finalized ? 2 : 0);
}

int verbss_mpi_world(void) { return (int)MPI_Comm_c2f(MPI_COMM_WORLD); }

/* 1 when `handle` names a communicator other than MPI_COMM_NULL (Open MPI
 * gives a null pointer for a handle it does not know). */
int verbss_mpi_valid(int handle) {
    MPI_Comm c = MPI_Comm_f2c(handle);
    return c != MPI_COMM_NULL && c != (MPI_Comm)0;
}

int verbss_mpi_rank(int comm, int *rank) { return MPI_Comm_rank(MPI_Comm_f2c(comm), rank); }

int verbss_mpi_size(int comm, int *size) { return MPI_Comm_size(MPI_Comm_f2c(comm), size); }

int verbss_mpi_barrier(int comm) { return MPI_Barrier(MPI_Comm_f2c(comm)); }

/* `count` values, each reduced over the ranks: `op` 0 is MPI_SUM, 1
 * MPI_MAX, 2 MPI_MIN. */
int verbss_mpi_allreduce(int comm, const void *in, void *out, int count, int type, int op) {
    MPI_Op reduction = op == 0 ? MPI_SUM : (op == 1 ? MPI_MAX : MPI_MIN);
    return MPI_Allreduce(in, out, count, datatype(type), reduction, MPI_Comm_f2c(comm));
}

int verbss_mpi_bcast(int comm, void *data, int count, int type, int root) {
    return MPI_Bcast(data, count, datatype(type), root, MPI_Comm_f2c(comm));
}

/* One int to and from each rank. */
int verbss_mpi_alltoall_int(int comm, const int *send, int *recv) {
    return MPI_Alltoall(send, 1, MPI_INT, recv, 1, MPI_INT, MPI_Comm_f2c(comm));
}

int verbss_mpi_alltoallv(int comm, const void *send, const int *scounts, const int *sdispls,
                         void *recv, const int *rcounts, const int *rdispls, int type) {
    MPI_Datatype t = datatype(type);
    return MPI_Alltoallv(send, scounts, sdispls, t, recv, rcounts, rdispls, t,
                         MPI_Comm_f2c(comm));
}

/* Every rank's int, in rank order. */
int verbss_mpi_allgather_int(int comm, int value, int *all) {
    return MPI_Allgather(&value, 1, MPI_INT, all, 1, MPI_INT, MPI_Comm_f2c(comm));
}

int verbss_mpi_allgatherv(int comm, const void *send, int count, void *recv, const int *counts,
                          const int *displs, int type) {
    MPI_Datatype t = datatype(type);
    return MPI_Allgatherv(send, count, t, recv, counts, displs, t, MPI_Comm_f2c(comm));
}

/* Neighbour k of `n`: `recv_len[k]` doubles from rank `ranks[k]` into
 * `recv[k]` and `send_len[k]` doubles of `send[k]` to it, all posted
 * non-blocking (receives first, tag 0) and waited for. Empty lists post
 * nothing. */
int verbss_mpi_exchange(int comm, int n, const int *ranks, const double *const *send,
                        const int *send_len, double *const *recv, const int *recv_len) {
    MPI_Comm c = MPI_Comm_f2c(comm);
    MPI_Request *requests = malloc(2 * (size_t)n * sizeof(MPI_Request) + 1);
    int count = 0, status = MPI_SUCCESS;
    if (requests == NULL) {
        return MPI_ERR_NO_MEM;
    }
    for (int k = 0; k < n && status == MPI_SUCCESS; k++) {
        if (recv_len[k] > 0) {
            status = MPI_Irecv(recv[k], recv_len[k], MPI_DOUBLE, ranks[k], 0, c, &requests[count++]);
        }
    }
    for (int k = 0; k < n && status == MPI_SUCCESS; k++) {
        if (send_len[k] > 0) {
            status = MPI_Isend(send[k], send_len[k], MPI_DOUBLE, ranks[k], 0, c, &requests[count++]);
        }
    }
    if (status == MPI_SUCCESS) {
        status = MPI_Waitall(count, requests, MPI_STATUSES_IGNORE);
    }
    free(requests);
    return status;
}

/* The bits of METIS's idx_t. */
int verbss_metis_idx_bits(void) { return (int)(8 * sizeof(idx_t)); }

/* METIS_PartGraphKway of the CSR graph (`xadj`, `adjncy`) with `n` vertices
 * into `nparts` parts, with METIS's default options but the seed 1; the part
 * of each vertex in `part`. The caller has checked that every number fits
 * idx_t. */
int verbss_metis_part_kway(size_t n, const size_t *xadj, const size_t *adjncy, size_t nparts,
                           int32_t *part) {
    idx_t options[METIS_NOPTIONS];
    idx_t nv = (idx_t)n, ncon = 1, np = (idx_t)nparts, cut = 0;
    size_t edges = xadj[n];
    idx_t *x = malloc(sizeof(idx_t) * (n + 1));
    idx_t *a = malloc(sizeof(idx_t) * edges + 1);
    idx_t *p = malloc(sizeof(idx_t) * n + 1);
    int status = METIS_ERROR_MEMORY;
    if (x != NULL && a != NULL && p != NULL) {
        for (size_t i = 0; i <= n; i++) {
            x[i] = (idx_t)xadj[i];
        }
        for (size_t i = 0; i < edges; i++) {
            a[i] = (idx_t)adjncy[i];
        }
        METIS_SetDefaultOptions(options);
        options[METIS_OPTION_SEED] = 1;
        status = METIS_PartGraphKway(&nv, &ncon, x, a, NULL, NULL, NULL, &np, NULL, NULL, options,
                                     &cut, p);
        for (size_t i = 0; status == METIS_OK && i < n; i++) {
            part[i] = (int32_t)p[i];
        }
    }
    free(x);
    free(a);
    free(p);
    return status;
}
