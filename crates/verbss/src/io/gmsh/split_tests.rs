//! The split sets: Gmsh's (`gmsh -part 3 -part_split`) read as the single
//! partitioned file of the same partitions, ours written and read back
//! bit for bit, and the sets refused.

use std::collections::{BTreeMap, BTreeSet};
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use super::partitioned::{read_share, Share};
use super::split::{read_split, split_count};
use super::split_write::{write_split_piece_to, SplitGroup, SplitModel, SplitPiece};
use crate::io::write_atomic;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes/gmsh")
        .join(name)
}

const SINGLE: &str = "channel_hole_part3_v41_ascii.msh";
const GMSH_SET: &str = "channel_hole_split3_v41_ascii_1.msh";

/// Per node tag: coordinates, boundary flag and groups.
type Nodes = BTreeMap<u64, (Vec<f64>, bool, BTreeSet<String>)>;

/// What a share holds, by tag: its nodes, its cells' tags (with their
/// nodes' tags) and each group's facets (as sets of node tags).
fn summary(share: &Share) -> (Nodes, BTreeMap<u64, Vec<u64>>, BTreeMap<String, usize>) {
    let mesh = &share.mesh;
    let mut nodes: Nodes = BTreeMap::new();
    for (i, &t) in mesh.node_tags.iter().enumerate() {
        let groups = share
            .group_nodes
            .iter()
            .filter(|(_, n)| n.contains(&i))
            .map(|(g, _)| g.clone())
            .collect();
        nodes.insert(t, (mesh.point(i).to_vec(), share.boundary[i], groups));
    }
    let tags = |nodes: &[usize]| nodes.iter().map(|&v| mesh.node_tags[v]).collect();
    let cells = (0..mesh.cell_count())
        .map(|c| (mesh.cell_tags[c], tags(mesh.cells.cell(c))))
        .collect();
    let facets = mesh
        .groups
        .iter()
        .map(|g| (g.name.clone(), g.facets.len()))
        .collect();
    (nodes, cells, facets)
}

/// Gmsh's split set gives, for any run of partitions, what the single
/// partitioned file of the same partitions gives.
#[test]
fn gmsh_split_set_reads_as_the_single_file() {
    assert_eq!(split_count(&fixture(GMSH_SET)).unwrap(), 3);
    let runs: [RangeInclusive<usize>; 5] = [1..=1, 2..=2, 3..=3, 2..=3, 1..=3];
    for wanted in runs {
        let split = read_split(&fixture(GMSH_SET), wanted.clone()).unwrap();
        let single = read_share(&fixture(SINGLE), wanted.clone()).unwrap();
        assert_eq!(split.partitions, 3);
        assert_eq!(summary(&split), summary(&single), "partitions {wanted:?}");
    }
}

/// The partitions of the single file written as a split set of our own
/// (ASCII and binary) read back as they were: coordinates bit for bit,
/// boundary and groups, cells and group facets.
#[test]
fn written_split_set_reads_back() {
    let shares: Vec<Share> = (1..=3)
        .map(|k| read_share(&fixture(SINGLE), k..=k).unwrap())
        .collect();
    let mut names: Vec<(String, usize, i32)> = Vec::new();
    for s in &shares {
        for g in &s.mesh.groups {
            let dim = g.facets.kinds.first().map_or(1, |k| k.dim());
            if !names.iter().any(|(n, ..)| *n == g.name) {
                names.push((g.name.clone(), dim, g.tag.unwrap()));
            }
        }
    }
    let groups: Vec<SplitGroup> = names
        .into_iter()
        .map(|(name, dim, physical)| SplitGroup {
            name,
            dim,
            physical,
        })
        .collect();
    let index = |s: &Share| -> Vec<usize> {
        s.mesh
            .groups
            .iter()
            .map(|g| groups.iter().position(|m| m.name == g.name).unwrap())
            .collect()
    };
    let indices: Vec<Vec<usize>> = shares.iter().map(index).collect();
    let tags: Vec<Vec<Vec<u64>>> = shares
        .iter()
        .map(|s| s.labels.facet_tags.clone().unwrap())
        .collect();
    let piece = |k: usize| SplitPiece {
        mesh: &shares[k].mesh,
        coords: &shares[k].mesh.coords,
        boundary: &shares[k].boundary,
        groups: &indices[k],
        facet_tags: &tags[k],
        partition: k + 1,
    };
    let mut model = SplitModel {
        dim: 2,
        groups: groups.clone(),
        domain: shares[0].labels.domain.clone().unwrap(),
        partitions: 3,
        entities: (0..3).flat_map(|k| piece(k).entities()).collect(),
    };
    model.entities.sort_by_key(|e| (e.partition, e.parent));
    for binary in [false, true] {
        let dir = tempfile::tempdir().unwrap();
        for k in 0..3 {
            let path = dir.path().join(format!("set_{}.msh", k + 1));
            write_atomic(&path, |w| {
                write_split_piece_to(w, &model, &piece(k), binary)
            })
            .unwrap();
        }
        let first = dir.path().join("set_1.msh");
        for wanted in [1..=1, 2..=3, 1..=3] {
            let back = read_split(&first, wanted.clone()).unwrap();
            let single = read_share(&fixture(SINGLE), wanted.clone()).unwrap();
            assert_eq!(back.binary, binary);
            let (nodes, cells, facets) = summary(&back);
            let (want_nodes, want_cells, want_facets) = summary(&single);
            assert_eq!(cells, want_cells, "partitions {wanted:?}");
            assert_eq!(facets, want_facets, "partitions {wanted:?}");
            // The groups a share joins with the others' are the facets'.
            for (tag, (x, boundary, _)) in &want_nodes {
                assert_eq!(&nodes[tag].0, x, "node {tag}");
                assert_eq!(nodes[tag].1, *boundary, "node {tag}");
            }
            assert_eq!(nodes.len(), want_nodes.len());
        }
    }
}

/// A set named otherwise than by `NAME_1.msh`, missing a file, with a file
/// too many, of files of different partition counts, of a file holding
/// another partition, or of an unpartitioned file is refused, naming the
/// file and what was expected.
#[test]
fn split_sets_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let set = |k: usize| dir.path().join(format!("set_{k}.msh"));
    let copy_gmsh = |k: usize, to: usize| {
        let from = fixture(&format!("channel_hole_split3_v41_ascii_{k}.msh"));
        std::fs::copy(from, set(to)).unwrap();
    };
    let error = |first: &Path, wanted| read_split(first, wanted).unwrap_err().to_string();
    (1..=3).for_each(|k| copy_gmsh(k, k));
    assert!(read_split(&set(1), 1..=3).is_ok());
    let e = error(&set(2), 2..=2);
    assert!(
        e.contains("set_2.msh: a split set is named by its first file, NAME_1.msh"),
        "{e}"
    );
    let e = error(&set(1), 1..=4);
    assert!(e.contains("partitions 1..=4 of the set"), "{e}");
    std::fs::copy(set(3), set(4)).unwrap();
    let e = error(&set(1), 1..=3);
    assert!(e.contains("set_4.msh exists, but"), "{e}");
    assert!(e.contains("set_1.msh declares 3 partitions"), "{e}");
    std::fs::remove_file(set(4)).unwrap();
    copy_gmsh(3, 2);
    let e = error(&set(1), 2..=2);
    assert!(e.contains("set_2.msh:"), "{e}");
    assert!(e.contains("(is "), "{e}");
    assert!(e.contains("set_2.msh partition 2 of the set?)"), "{e}");
    std::fs::copy(fixture("box_part6_v41_ascii.msh"), set(2)).unwrap();
    let e = error(&set(1), 2..=2);
    assert!(e.contains("set_2.msh declares 6 partitions, "), "{e}");
    std::fs::remove_file(set(2)).unwrap();
    let e = error(&set(1), 1..=1);
    assert!(e.contains("set_2.msh: missing: "), "{e}");
    std::fs::copy(fixture("channel_hole_v41_ascii.msh"), set(1)).unwrap();
    let e = error(&set(1), 1..=1);
    assert!(e.contains("set_1.msh: not a partitioned file"), "{e}");
}
