#!/usr/bin/env bash
# Regenerates the README's pictures: bash docs/images/generate.sh (from the
# repository root). Runs the demo (160 steps, about 15 s) into out/demo and
# draws with `verbss render`.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -p verbss-cli
verbss=target/release/verbss
su2=assets/meshes/su2

# The demo's airfoil at its extreme pitch (step 40 of 160: +40°, plunged 0.2 chord).
$verbss demo --out out/demo --quiet
$verbss render out/demo/naca0012_0040.vtu -o docs/images/demo_pitch40.png \
  --view -0.6,1.6,-1,1 --width 1000 --title "verbss demo, step 40: pitch 40°, plunge 0.2"

# A 3D mesh: the tetrahedral brick's boundary surface, and a cut through it.
$verbss render $su2/mesh_brick_tets_ffd.su2 -o docs/images/brick_tets_surface.png --width 1000
$verbss render $su2/mesh_brick_tets_ffd.su2 -o docs/images/brick_tets_cut.png --cut y=0.5 --width 1000

# The hybrid RAE2822 mesh near its trailing edge: quads in the boundary layer.
$verbss render $su2/mesh_RAE2822_turb_ffd.su2 -o docs/images/rae2822_trailing_edge.png \
  --view 0.95,1.03,-0.025,0.015 --width 1000
