/* Writes the hand-made CGNS fixtures (ADF files, the smallest the library
 * writes) of the tests of the distributed CGNS read
 * (crates/verbss-mpi/tests/cgns_blocks.rs): the broken ones under
 * assets/meshes/bad/, the one of groups under assets/meshes/cgns/. Run from
 * the repository root (needs libcgns-dev):
 *   cc scripts/make_cgns_fixtures.c -o /tmp/make_cgns_fixtures -lcgns
 *   (cd assets/meshes && /tmp/make_cgns_fixtures)
 */
#include <stdio.h>
#include <cgnslib.h>
/* Stops with the library's message when a call fails. */
#define OK(x) if (x) { printf("%s\n", cg_get_error()); return 1; }
/* A unit square: two triangles (elements 1, 2) and the section `wall` of two
 * edges (3, 4), with `extra`: 1 a condition over elements 3..9, of which
 * no section holds 5..9; 2 a second zone; 3 a polyhedral section; 4 no
 * section of cells; 5 a condition over elements 3..2000000002; 6 the
 * first triangle twice (elements 1 and 3, the edges 4 and 5); 7 a condition
 * `bottom` over the element list {3} in the family `solid`, and a section
 * `lid` (element 5) that no condition holds. */
static int square(const char *name, int extra) {
  int f, b, z, s, bc;
  cgsize_t size[3] = {4, 2, 0};
  double x[4] = {0, 1, 1, 0}, y[4] = {0, 0, 1, 1};
  cgsize_t tri[6] = {1, 2, 3, 1, 3, 4}, bar[4] = {1, 2, 2, 3}, lid[2] = {3, 4};
  OK(cg_open(name, CG_MODE_WRITE, &f));
  OK(cg_base_write(f, "Base", 2, 2, &b));
  OK(cg_zone_write(f, b, "Zone", size, Unstructured, &z));
  OK(cg_coord_write(f, b, z, RealDouble, "CoordinateX", x, &s));
  OK(cg_coord_write(f, b, z, RealDouble, "CoordinateY", y, &s));
  if (extra == 6) { /* 6: the first triangle twice */
    cgsize_t twice[9] = {1, 2, 3, 1, 3, 4, 1, 2, 3};
    OK(cg_section_write(f, b, z, "Cells", TRI_3, 1, 3, 0, twice, &s));
    OK(cg_section_write(f, b, z, "wall", BAR_2, 4, 5, 0, bar, &s));
  } else {
    if (extra != 4) /* 4: no section of cells */
      OK(cg_section_write(f, b, z, "Cells", TRI_3, 1, 2, 0, tri, &s));
    OK(cg_section_write(f, b, z, "wall", BAR_2, 3, 4, 0, bar, &s));
  }
  if (extra == 1) { /* a condition naming element 9, which no section holds */
    cgsize_t range[2] = {3, 9};
    OK(cg_boco_write(f, b, z, "wall", BCWall, ElementRange, 2, range, &bc));
  }
  if (extra == 5) { /* a condition over two thousand million elements */
    cgsize_t range[2] = {3, 2000000002};
    OK(cg_boco_write(f, b, z, "wall", BCWall, ElementRange, 2, range, &bc));
  }
  if (extra == 7) { /* a condition over element 3 only, in the family `solid` */
    cgsize_t list[1] = {3};
    int fam;
    OK(cg_family_write(f, b, "solid", &fam));
    OK(cg_boco_write(f, b, z, "bottom", FamilySpecified, ElementList, 1, list, &bc));
    OK(cg_goto(f, b, "Zone_t", z, "ZoneBC_t", 1, "BC_t", bc, "end"));
    OK(cg_famname_write("solid"));
    OK(cg_section_write(f, b, z, "lid", BAR_2, 5, 5, 0, lid, &s));
  }
  if (extra == 2) { /* a second zone */
    cgsize_t size2[3] = {3, 1, 0};
    double x2[3] = {5, 6, 5}, y2[3] = {5, 5, 6};
    cgsize_t tri2[3] = {1, 2, 3};
    OK(cg_zone_write(f, b, "Zone2", size2, Unstructured, &z));
    OK(cg_coord_write(f, b, z, RealDouble, "CoordinateX", x2, &s));
    OK(cg_coord_write(f, b, z, RealDouble, "CoordinateY", y2, &s));
    OK(cg_section_write(f, b, z, "Cells", TRI_3, 1, 1, 0, tri2, &s));
  }
  if (extra == 3) { /* a polyhedral section */
    cgsize_t ngon[3] = {2, 1, 2}, off[2] = {0, 3};
    OK(cg_poly_section_write(f, b, z, "Faces", NGON_n, 5, 5, 0, ngon, off, &s));
  }
  OK(cg_close(f));
  return 0;
}
int main(void) {
  int f, b, z;
  cgsize_t size[9] = {2, 2, 1, 1, 0, 0};
  OK(cg_set_file_type(CG_FILE_ADF));
  OK(cg_open("bad/structured.cgns", CG_MODE_WRITE, &f));
  OK(cg_base_write(f, "Grid", 2, 2, &b));
  OK(cg_zone_write(f, b, "Block", size, Structured, &z));
  OK(cg_close(f));
  return square("bad/condition_outside.cgns", 1) || square("bad/two_zones.cgns", 2) || square("bad/polyhedral.cgns", 3)
      || square("bad/no_cells.cgns", 4) || square("bad/huge_range.cgns", 5)
      || square("bad/duplicated.cgns", 6) || square("cgns/list_and_own_section.cgns", 7);
}
