/*
 * deform.c: a flow solver's view of verbss, through its C API.
 *
 * Reads an SU2 mesh (ASCII), moves the nodes of one marker by a translation
 * reached in STEPS equal steps, calling verbss once per time step, and
 * writes the final coordinates of every node to OUT, one node per line.
 * Each NAME=VALUE is a setting, named and spelled as on the command line
 * with `_` for `-` (tolerance=1e-5, method=verbss, rigid_layer=0.1, …);
 * slide=MARKER makes a marker slide in its own plane, and
 * slide=MARKER:NX,NY[,NZ] in the plane of that normal; fixed=MARKER keeps
 * a marker where it is, with the nodes where a sliding marker meets it (the
 * mesh file's other markers, for the command).
 *
 *     deform MESH.su2 MARKER STEPS OUT DX DY [DZ] [NAME=VALUE …]
 *
 * does what `verbss deform MESH.su2 -o OUT.su2 --moving MARKER --translate
 * DX,DY[,DZ] --steps STEPS --NAME VALUE … --slide MARKER …` does, given
 * fixed=M for each marker M that neither moves nor slides.
 *
 * Build (from the repository root, after `cargo build -p verbss-capi`):
 *
 *     cc -std=c99 -O2 examples/c/deform.c -Iinclude -Ltarget/debug \
 *        -lverbss_capi -Wl,-rpath,$PWD/target/debug -o deform
 *     ./deform assets/meshes/su2/mesh_NACA0012_inv.su2 airfoil 4 out.txt 0.1 0.05 \
 *        tolerance=1e-5 predictor=linear
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "verbss.h"

/* An SU2 mesh: coordinates, cells as VTK kinds + concatenated nodes. */
typedef struct {
    size_t dim, n_points, n_cells, n_cell_nodes;
    double *points;
    int32_t *kinds;
    int64_t *cell_nodes;
} Su2;

/* The distinct nodes of a marker, sorted. */
typedef struct {
    size_t n;
    int64_t *ids;
} Marker;

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

/* Reads the coordinates and the cells; returns 0 on success. */
static int read_su2(const char *path, Su2 *m) {
    FILE *f = fopen(path, "r");
    char line[4096];
    long value;
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
        }
    }
    fclose(f);
    return 0;
}

/* Reads the distinct nodes of the marker `name`; returns 0 on success. */
static int read_marker(const char *path, const char *name, Marker *out) {
    FILE *f = fopen(path, "r");
    char line[4096];
    long value;
    int in_marker = 0;
    size_t cap = 0;
    memset(out, 0, sizeof *out);
    if (!f) {
        perror(path);
        return 1;
    }
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "MARKER_TAG=", 11) == 0) {
            char tag[256];
            in_marker = sscanf(line + 11, " %255s", tag) == 1 && strcmp(tag, name) == 0;
        } else if (in_marker && keyword(line, "MARKER_ELEMS", &value)) {
            for (long e = 0; e < value; e++) {
                long kind;
                if (fscanf(f, "%ld", &kind) != 1 || nodes_of(kind) == 0) {
                    fprintf(stderr, "%s: marker %s: bad element\n", path, name);
                    return 1;
                }
                for (int k = 0; k < nodes_of(kind); k++) {
                    long long id;
                    if (fscanf(f, "%lld", &id) != 1) {
                        fprintf(stderr, "%s: marker %s: missing node\n", path, name);
                        return 1;
                    }
                    if (out->n == cap) {
                        cap = 2 * cap + 64;
                        out->ids = realloc(out->ids, cap * sizeof *out->ids);
                    }
                    out->ids[out->n++] = (int64_t)id;
                }
            }
            in_marker = 0;
        }
    }
    fclose(f);
    qsort(out->ids, out->n, sizeof *out->ids, by_value);
    size_t distinct = 0;
    for (size_t k = 0; k < out->n; k++) {
        if (distinct == 0 || out->ids[distinct - 1] != out->ids[k]) {
            out->ids[distinct++] = out->ids[k];
        }
    }
    out->n = distinct;
    if (out->n == 0) {
        fprintf(stderr, "%s: no marker %s\n", path, name);
        return 1;
    }
    return 0;
}

/* Prints the API's message for a failed call and returns its status. */
static int fail(const char *call, int status) {
    fprintf(stderr, "%s failed (status %d): %s\n", call, status, verbss_last_error());
    return status;
}

/* fixed=MARKER: adds the marker's fixed group; returns a status, or -1 when
 * the marker cannot be read. */
static int add_fixed(const char *path, const char *name, VerbssSettings *settings) {
    Marker marker;
    if (read_marker(path, name, &marker) != 0) {
        return -1;
    }
    int status = verbss_settings_add_fixed(settings, marker.ids, marker.n);
    free(marker.ids);
    return status;
}

/* slide=MARKER or slide=MARKER:NX,NY[,NZ]: adds the marker's sliding plane;
 * returns a status, or -1 when the marker cannot be read. */
static int add_slide(const char *path, char *spec, VerbssSettings *settings) {
    double normal[3];
    int n_normal = 0;
    char *colon = strchr(spec, ':');
    if (colon) {
        *colon = '\0';
        n_normal = sscanf(colon + 1, "%lf,%lf,%lf", &normal[0], &normal[1], &normal[2]);
        n_normal = n_normal < 0 ? 0 : n_normal;
    }
    Marker marker;
    if (read_marker(path, spec, &marker) != 0) {
        return -1;
    }
    int status = verbss_settings_add_slide(settings, marker.ids, marker.n,
                                           n_normal ? normal : NULL, (size_t)n_normal);
    free(marker.ids);
    return status;
}

int main(int argc, char **argv) {
    if (argc < 7) {
        fprintf(stderr, "usage: %s MESH.su2 MARKER STEPS OUT DX DY [DZ] [NAME=VALUE ...]\n",
                argv[0]);
        return 1;
    }
    Su2 m;
    Marker moving;
    if (read_su2(argv[1], &m) != 0 || read_marker(argv[1], argv[2], &moving) != 0) {
        return 1;
    }
    int steps = atoi(argv[3]);

    /* The translation, then the settings: the defaults of `verbss deform`
     * with each NAME=VALUE over them. */
    double shift[3] = {0.0, 0.0, 0.0};
    size_t n_shift = 0;
    VerbssSettings *settings = NULL;
    const char *call = "verbss_settings_new";
    int status = verbss_settings_new(&settings);
    for (int a = 5; a < argc && status == VERBSS_OK; a++) {
        char *eq = strchr(argv[a], '=');
        if (!eq) {
            if (n_shift == m.dim) {
                fprintf(stderr, "%s: more than %zu numbers in the translation\n", argv[a], m.dim);
                return 1;
            }
            shift[n_shift++] = atof(argv[a]);
            continue;
        }
        *eq = '\0';
        if (strcmp(argv[a], "slide") == 0) {
            call = "verbss_settings_add_slide";
            status = add_slide(argv[1], eq + 1, settings);
        } else if (strcmp(argv[a], "fixed") == 0) {
            call = "verbss_settings_add_fixed";
            status = add_fixed(argv[1], eq + 1, settings);
        } else {
            call = "verbss_settings_set";
            status = verbss_settings_set(settings, argv[a], eq + 1);
        }
    }
    if (status < 0) {
        return 1;
    }
    if (status != VERBSS_OK) {
        return fail(call, status);
    }

    /* Once per mesh: the deformer. It keeps a copy of the settings. */
    VerbssDeformer *deformer = NULL;
    status = verbss_deformer_new(m.dim, m.points, m.n_points, m.kinds, m.n_cells,
                                 m.cell_nodes, m.n_cell_nodes, moving.ids, moving.n,
                                 settings, &deformer);
    verbss_settings_free(settings);
    if (status != VERBSS_OK) {
        return fail("verbss_deformer_new", status);
    }

    /* Once per time step: the marker's displacement from the input mesh. */
    double *u = malloc(moving.n * m.dim * sizeof *u);
    for (int n = 1; n <= steps; n++) {
        double f = (double)n / (double)steps;
        for (size_t k = 0; k < moving.n; k++) {
            for (size_t d = 0; d < m.dim; d++) {
                u[m.dim * k + d] = f * shift[d];
            }
        }
        status = verbss_deformer_step(deformer, u, moving.n * m.dim);
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
    FILE *out = fopen(argv[4], "w");
    if (!out) {
        perror(argv[4]);
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
    free(moving.ids);
    return 0;
}
