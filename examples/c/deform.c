/*
 * deform.c: a flow solver's view of verbss, through its C API.
 *
 * Reads an SU2 mesh (ASCII), moves the nodes of one marker by a translation
 * reached in STEPS equal steps (as `verbss deform MESH --moving MARKER
 * --translate DX,DY[,DZ] --steps STEPS` does), calling verbss once per time
 * step, and writes the final coordinates of every node to OUT, one node per
 * line. TOL is the solver's relative tolerance (the default settings'
 * 1e-5, or larger for a quicker, coarser solve).
 *
 *     deform MESH.su2 MARKER STEPS TOL OUT DX DY [DZ]
 *
 * Build (from the repository root, after `cargo build -p verbss-capi`):
 *
 *     cc -std=c99 -O2 examples/c/deform.c -Iinclude -Ltarget/debug \
 *        -lverbss_capi -Wl,-rpath,$PWD/target/debug -o deform
 *     ./deform assets/meshes/su2/mesh_NACA0012_inv.su2 airfoil 4 1e-5 out.txt 0.1 0.05
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "verbss.h"

/* An SU2 mesh: coordinates, cells as VTK kinds + concatenated nodes, and the
 * distinct nodes of one marker. */
typedef struct {
    size_t dim, n_points, n_cells, n_cell_nodes, n_marker;
    double *points;
    int32_t *kinds;
    int64_t *cell_nodes;
    int64_t *marker;
} Su2;

static int nodes_of(long kind) {
    switch (kind) {
    case 3: return 2;                 /* line */
    case VERBSS_TRIANGLE: return 3;
    case VERBSS_QUAD: return 4;
    case VERBSS_TETRA: return 4;
    case VERBSS_HEXAHEDRON: return 8;
    case VERBSS_WEDGE: return 6;
    case VERBSS_PYRAMID: return 5;
    default: return 0;
    }
}

static int by_value(const void *a, const void *b) {
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

/* Skips the rest of the current line. */
static void skip_line(FILE *f) {
    int c;
    while ((c = fgetc(f)) != EOF && c != '\n') {
    }
}

/* Reads the value after "KEY=" on a line that starts with KEY. */
static int keyword(const char *line, const char *key, long *value) {
    size_t n = strlen(key);
    return strncmp(line, key, n) == 0 && sscanf(line + n, " = %ld", value) == 1;
}

/* Reads the mesh and the nodes of `marker`; returns 0 on success. */
static int read_su2(const char *path, const char *marker, Su2 *m) {
    FILE *f = fopen(path, "r");
    char line[4096];
    long value;
    int in_marker = 0;
    size_t cap_marker = 0;
    memset(m, 0, sizeof *m);
    if (!f) {
        perror(path);
        return 1;
    }
    while (fgets(line, sizeof line, f)) {
        if (keyword(line, "NDIME", &value)) {
            m->dim = (size_t)value;
        } else if (keyword(line, "NELEM", &value)) {
            m->n_cells = (size_t)value;
            m->kinds = malloc(m->n_cells * sizeof *m->kinds);
            m->cell_nodes = malloc(m->n_cells * 8 * sizeof *m->cell_nodes);
            for (size_t c = 0; c < m->n_cells; c++) {
                long kind;
                if (fscanf(f, "%ld", &kind) != 1 || nodes_of(kind) == 0) {
                    fprintf(stderr, "%s: element %zu: bad type\n", path, c);
                    return 1;
                }
                m->kinds[c] = (int32_t)kind;
                for (int k = 0; k < nodes_of(kind); k++) {
                    long long id;
                    if (fscanf(f, "%lld", &id) != 1) {
                        fprintf(stderr, "%s: element %zu: missing node\n", path, c);
                        return 1;
                    }
                    m->cell_nodes[m->n_cell_nodes++] = (int64_t)id;
                }
                skip_line(f); /* the element's index */
            }
        } else if (keyword(line, "NPOIN", &value)) {
            m->n_points = (size_t)value;
            m->points = malloc(m->n_points * m->dim * sizeof *m->points);
            for (size_t i = 0; i < m->n_points; i++) {
                for (size_t d = 0; d < m->dim; d++) {
                    if (fscanf(f, "%lf", &m->points[m->dim * i + d]) != 1) {
                        fprintf(stderr, "%s: point %zu: missing coordinate\n", path, i);
                        return 1;
                    }
                }
                skip_line(f); /* the point's index */
            }
        } else if (strncmp(line, "MARKER_TAG=", 11) == 0) {
            char name[256];
            in_marker = sscanf(line + 11, " %255s", name) == 1 && strcmp(name, marker) == 0;
        } else if (in_marker && keyword(line, "MARKER_ELEMS", &value)) {
            for (long e = 0; e < value; e++) {
                long kind;
                if (fscanf(f, "%ld", &kind) != 1 || nodes_of(kind) == 0) {
                    fprintf(stderr, "%s: marker %s: bad element\n", path, marker);
                    return 1;
                }
                for (int k = 0; k < nodes_of(kind); k++) {
                    long long id;
                    if (fscanf(f, "%lld", &id) != 1) {
                        fprintf(stderr, "%s: marker %s: missing node\n", path, marker);
                        return 1;
                    }
                    if (m->n_marker == cap_marker) {
                        cap_marker = 2 * cap_marker + 64;
                        m->marker = realloc(m->marker, cap_marker * sizeof *m->marker);
                    }
                    m->marker[m->n_marker++] = (int64_t)id;
                }
            }
            in_marker = 0;
        }
    }
    fclose(f);
    /* The marker's distinct nodes, sorted. */
    qsort(m->marker, m->n_marker, sizeof *m->marker, by_value);
    size_t distinct = 0;
    for (size_t k = 0; k < m->n_marker; k++) {
        if (distinct == 0 || m->marker[distinct - 1] != m->marker[k]) {
            m->marker[distinct++] = m->marker[k];
        }
    }
    m->n_marker = distinct;
    if (m->n_marker == 0) {
        fprintf(stderr, "%s: no marker %s\n", path, marker);
        return 1;
    }
    return 0;
}

/* Prints the API's message for a failed call and returns its status. */
static int fail(const char *call, int status) {
    fprintf(stderr, "%s failed (status %d): %s\n", call, status, verbss_last_error());
    return status;
}

int main(int argc, char **argv) {
    if (argc < 8 || argc > 9) {
        fprintf(stderr, "usage: %s MESH.su2 MARKER STEPS TOL OUT DX DY [DZ]\n", argv[0]);
        return 1;
    }
    Su2 m;
    if (read_su2(argv[1], argv[2], &m) != 0) {
        return 1;
    }
    int steps = atoi(argv[3]);
    double shift[3] = {0.0, 0.0, 0.0};
    for (int d = 6; d < argc; d++) {
        shift[d - 6] = atof(argv[d]);
    }

    /* Once per mesh: the deformer, with the default settings but TOL. */
    VerbssSettings settings;
    verbss_settings_default(&settings);
    settings.tolerance = atof(argv[4]);
    VerbssDeformer *deformer = NULL;
    int status = verbss_deformer_new(m.dim, m.points, m.n_points, m.kinds, m.n_cells,
                                     m.cell_nodes, m.n_cell_nodes, m.marker, m.n_marker,
                                     &settings, &deformer);
    if (status != VERBSS_OK) {
        return fail("verbss_deformer_new", status);
    }

    /* Once per time step: the marker's displacement from the input mesh. */
    double *u = malloc(m.n_marker * m.dim * sizeof *u);
    for (int n = 1; n <= steps; n++) {
        double f = (double)n / (double)steps;
        for (size_t k = 0; k < m.n_marker; k++) {
            for (size_t d = 0; d < m.dim; d++) {
                u[m.dim * k + d] = f * shift[d];
            }
        }
        status = verbss_deformer_step(deformer, u, m.n_marker * m.dim);
        if (status != VERBSS_OK) {
            verbss_deformer_free(deformer);
            return fail("verbss_deformer_step", status);
        }
        VerbssInfo info;
        verbss_deformer_info(deformer, &info);
        printf("step %zu: %zu sweeps, residual %.3e, min quality %.4f, %.3f s\n", info.step,
               info.iterations, info.residual, info.min_quality, info.seconds);
    }

    /* The new coordinates of every node. */
    status = verbss_deformer_points(deformer, m.points, m.n_points * m.dim);
    verbss_deformer_free(deformer);
    if (status != VERBSS_OK) {
        return fail("verbss_deformer_points", status);
    }
    FILE *out = fopen(argv[5], "w");
    if (!out) {
        perror(argv[5]);
        return 1;
    }
    for (size_t i = 0; i < m.n_points; i++) {
        for (size_t d = 0; d < m.dim; d++) {
            fprintf(out, d + 1 < m.dim ? "%.17g " : "%.17g\n", m.points[m.dim * i + d]);
        }
    }
    fclose(out);
    free(u);
    free(m.points);
    free(m.kinds);
    free(m.cell_nodes);
    free(m.marker);
    return 0;
}
