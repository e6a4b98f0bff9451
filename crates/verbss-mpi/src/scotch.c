/* The PT-Scotch call of verbss-mpi behind plain C types (see src/shim.c);
 * build.rs compiles this file only when it has found PT-Scotch. */

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <mpi.h>
#include <ptscotch.h>

/* PT-Scotch's partition of the distributed graph of which this rank holds
 * `n` vertices, numbered after those of the lower ranks: vertex i's
 * neighbours are the global numbers `targets[offsets[i]..offsets[i + 1]]`
 * (the graph symmetric, without self loops). Cuts it into `parts` parts with
 * the default strategy in a deterministic context with the fixed random
 * seed 1, so that the same graph on the same ranks gives the same parts;
 * the part of each local vertex in `part`. Returns 0; 1 when a number does
 * not fit SCOTCH_Num; 2 when PT-Scotch fails (it has said why on stderr);
 * 3 out of memory. Collective. */
int verbss_scotch_part(int comm, size_t n, const uint64_t *offsets, const uint64_t *targets,
                       uint64_t vertices, int parts, int32_t *part) {
    const uint64_t limit = sizeof(SCOTCH_Num) == 4 ? (uint64_t)INT32_MAX : (uint64_t)INT64_MAX;
    size_t edges = (size_t)offsets[n];
    int status = 0;
    if (vertices > limit || offsets[n] > limit || (uint64_t)parts > limit) {
        status = 1;
    }
    for (size_t i = 0; status == 0 && i < edges; i++) {
        if (targets[i] >= vertices) {
            status = 1;
        }
    }
    /* Every rank must take the same way: one failing rank stops them all. */
    MPI_Comm c = MPI_Comm_f2c(comm);
    int worst = 0;
    MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, c);
    if (worst != 0) {
        return worst;
    }
    SCOTCH_Num *vert = malloc(sizeof(SCOTCH_Num) * (n + 1));
    SCOTCH_Num *edge = malloc(sizeof(SCOTCH_Num) * edges + 1);
    SCOTCH_Num *p = malloc(sizeof(SCOTCH_Num) * n + 1);
    status = (vert == NULL || edge == NULL || p == NULL) ? 3 : 0;
    MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, c);
    if (worst == 0) {
        for (size_t i = 0; i <= n; i++) {
            vert[i] = (SCOTCH_Num)offsets[i];
        }
        for (size_t i = 0; i < edges; i++) {
            edge[i] = (SCOTCH_Num)targets[i];
        }
        SCOTCH_Context context;
        SCOTCH_Dgraph graph, bound;
        SCOTCH_Strat strat;
        SCOTCH_contextInit(&context);
        SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1);
        SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1);
        SCOTCH_contextRandomClone(&context);
        SCOTCH_contextRandomSeed(&context, 1);
        SCOTCH_dgraphInit(&graph, c);
        SCOTCH_stratInit(&strat);
        int built = SCOTCH_dgraphBuild(&graph, 0, (SCOTCH_Num)n, (SCOTCH_Num)n, vert, NULL, NULL,
                                       NULL, (SCOTCH_Num)edges, (SCOTCH_Num)edges, edge, NULL,
                                       NULL);
        if (built == 0 && SCOTCH_contextBindDgraph(&context, &graph, &bound) == 0) {
            built = SCOTCH_dgraphPart(&bound, (SCOTCH_Num)parts, &strat, p);
            SCOTCH_dgraphExit(&bound);
        } else {
            built = 1;
        }
        worst = built != 0 ? 2 : 0;
        status = worst;
        MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, c);
        for (size_t i = 0; worst == 0 && i < n; i++) {
            part[i] = (int32_t)p[i];
        }
        SCOTCH_stratExit(&strat);
        SCOTCH_dgraphExit(&graph);
        SCOTCH_contextExit(&context);
    }
    free(vert);
    free(edge);
    free(p);
    return worst;
}
