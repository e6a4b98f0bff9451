//! Shares of the partitioned fixtures (written by Gmsh with 3 partitions,
//! `scripts/make_partitioned_fixtures.py`) against Gmsh's own counts and
//! against the whole file read at once; the errors of a share's reader; a
//! share written as a piece.

use std::collections::{BTreeSet, HashMap};
use std::path::Path;

use super::{fixture_dir, read_fixture};
use crate::io::gmsh::partitioned::{partition_count, read_share, Share};
use crate::topology::boundary_nodes;
use crate::Error;

/// The partitioned fixtures and their partition counts. In the box cut in
/// 6, Gmsh puts nodes that elements of one partition use on partition
/// boundary entities that do not list that partition.
const FILES: [(&str, usize); 3] = [
    ("channel_hole_part3_v41_ascii.msh", 3),
    ("box_part3_v41_binary.msh", 3),
    ("box_part6_v41_ascii.msh", 6),
];

fn share(name: &str, wanted: std::ops::RangeInclusive<usize>) -> Share {
    read_share(&fixture_dir().join(name), wanted).unwrap()
}

/// Each partition alone holds Gmsh's numbers of cells and of nodes on its
/// entities, and the nodes of its cells that Gmsh put on entities of other
/// partitions only (none but in the box cut in 6).
#[test]
fn each_partition_holds_gmsh_counts() {
    let text = std::fs::read_to_string(fixture_dir().join("partitions.json")).unwrap();
    let counts: serde_json::Value = serde_json::from_str(&text).unwrap();
    for (name, parts) in FILES {
        assert_eq!(partition_count(&fixture_dir().join(name)).unwrap(), parts);
        let mut elsewhere = 0;
        for p in 1..=parts {
            let want = &counts[name][p.to_string()];
            let s = share(name, p..=p);
            assert_eq!(s.partitions, parts);
            assert_eq!(
                s.mesh.cell_count() as u64,
                want["cells"].as_u64().unwrap(),
                "{name} {p}"
            );
            let on_entities = want["nodes"].as_u64().unwrap() as usize;
            assert!(s.mesh.node_count() >= on_entities, "{name} {p}");
            elsewhere += s.mesh.node_count() - on_entities;
        }
        assert_eq!(
            elsewhere > 0,
            parts == 6,
            "{name}: {elsewhere} nodes elsewhere"
        );
    }
}

/// The shares split the whole file's cells, each with its tag, nodes and
/// coordinates; their group facets add up to the whole file's; a node is
/// on the boundary in its share exactly when it is in the whole mesh, on a
/// group only when it is in the whole mesh, and joined over the shares
/// every group has all its nodes.
#[test]
fn shares_split_the_whole_mesh() {
    for (name, parts) in FILES {
        let whole = read_fixture(name);
        let dim = whole.dim;
        let node_of_tag: HashMap<u64, usize> = whole
            .node_tags
            .iter()
            .enumerate()
            .map(|(i, &t)| (t, i))
            .collect();
        let cell_of_tag: HashMap<u64, usize> = whole
            .cell_tags
            .iter()
            .enumerate()
            .map(|(c, &t)| (t, c))
            .collect();
        let boundary = boundary_nodes(&whole);
        let mut seen = vec![0; whole.cell_count()];
        let mut facets: HashMap<String, usize> = HashMap::new();
        let mut joined: HashMap<String, BTreeSet<usize>> = HashMap::new();
        for p in 1..=parts {
            let s = share(name, p..=p);
            assert_eq!(s.mesh.dim, dim);
            for (i, &t) in s.mesh.node_tags.iter().enumerate() {
                let g = node_of_tag[&t];
                assert_eq!(s.mesh.point(i), whole.point(g), "{name} node {t}");
                assert_eq!(s.boundary[i], boundary[g], "{name} node {t}");
            }
            for (c, &t) in s.mesh.cell_tags.iter().enumerate() {
                let w = cell_of_tag[&t];
                seen[w] += 1;
                let tags = |m: &crate::Mesh, c: usize| -> Vec<u64> {
                    m.cells.cell(c).iter().map(|&v| m.node_tags[v]).collect()
                };
                assert_eq!(tags(&s.mesh, c), tags(&whole, w), "{name} cell {t}");
            }
            for g in &s.mesh.groups {
                *facets.entry(g.name.clone()).or_default() += g.facets.len();
            }
            assert_eq!(s.group_nodes.len(), whole.groups.len(), "{name}");
            for (group, nodes) in &s.group_nodes {
                let want: BTreeSet<usize> =
                    whole.group(group).unwrap().nodes().into_iter().collect();
                for &i in nodes {
                    let g = node_of_tag[&s.mesh.node_tags[i]];
                    assert!(want.contains(&g), "{name} group {group} partition {p}");
                    joined.entry(group.clone()).or_default().insert(g);
                }
            }
        }
        // Joined over the shares (as the ranks do), every group is whole.
        for g in &whole.groups {
            let want: BTreeSet<usize> = g.nodes().into_iter().collect();
            assert_eq!(joined[&g.name], want, "{name} group {}", g.name);
        }
        assert!(
            seen.iter().all(|&n| n == 1),
            "{name}: every cell in one share"
        );
        for g in &whole.groups {
            assert_eq!(facets[&g.name], g.facets.len(), "{name} group {}", g.name);
        }
        let all = share(name, 1..=parts);
        assert_eq!(all.mesh.cell_count(), whole.cell_count());
        assert_eq!(all.mesh.node_count(), whole.node_count());
    }
}

/// The error of reading a share of `path`.
fn share_error(path: &Path, wanted: std::ops::RangeInclusive<usize>) -> String {
    read_share(path, wanted).unwrap_err().to_string()
}

#[test]
fn files_that_are_not_partitioned_msh41_are_refused() {
    let path = fixture_dir().join("box_v41_ascii.msh");
    assert_eq!(partition_count(&path).unwrap(), 0);
    let e = share_error(&path, 1..=1);
    assert!(e.contains("it is not partitioned"), "{e}");
    let e = share_error(&fixture_dir().join("box_v22_ascii.msh"), 1..=1);
    assert!(e.contains(":1: MSH 2.2 has no partitioned entities"), "{e}");
    let path = fixture_dir().join(FILES[0].0);
    for wanted in [0..=1, 2..=4] {
        match read_share(&path, wanted) {
            Err(Error::InvalidSetting(m)) => assert!(m.contains("which has 3"), "{m}"),
            other => panic!("{other:?}"),
        }
    }
}

/// A file cut short inside a block that is stepped over, and one whose
/// kept block has a bad number: the line or byte offset is named.
#[test]
fn errors_name_the_line_or_byte() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture_dir().join(FILES[0].0)).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let nodes = lines.iter().position(|l| *l == "$Nodes").unwrap();
    // The first node block's header, then half of its body.
    let (n, cut) = (nodes + 2, nodes + 4);
    let short = dir.path().join("short.msh");
    std::fs::write(&short, lines[..cut].join("\n") + "\n").unwrap();
    let e = share_error(&short, 3..=3);
    assert!(e.starts_with(&format!("{}:", short.display())), "{e}");
    assert!(
        e.contains("unexpected end of file: a node block holds"),
        "{e}"
    );
    // A block of partition 1 with a bad coordinate.
    let bad = dir.path().join("bad.msh");
    let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    let count: usize = lines[n].split(' ').nth(3).unwrap().parse().unwrap();
    let coordinate = n + 1 + count;
    edited[coordinate] = "0 x 0".into();
    std::fs::write(&bad, edited.join("\n") + "\n").unwrap();
    let e = share_error(&bad, 1..=3);
    assert_eq!(
        e,
        format!(
            "{}:{}: expected a coordinate, found 'x'",
            bad.display(),
            coordinate + 1
        )
    );
    // The same block stepped over (read for the other partitions): the
    // line is named as well.
    assert_eq!(
        share_error(&bad, 2..=3),
        format!(
            "{}:{}: a node block: expected a number, found 'x'",
            bad.display(),
            coordinate + 1
        )
    );
    // A block size no file can hold.
    let mut header: Vec<&str> = lines[n].split(' ').collect();
    header[3] = "18446744073709551615";
    edited[n] = header.join(" ");
    std::fs::write(&bad, edited.join("\n") + "\n").unwrap();
    assert_eq!(
        share_error(&bad, 1..=1),
        format!(
            "{}:{}: node block size 18446744073709551615 is too large",
            bad.display(),
            n + 1
        )
    );
    let bytes = std::fs::read(fixture_dir().join(FILES[1].0)).unwrap();
    let short = dir.path().join("short_binary.msh");
    std::fs::write(&short, &bytes[..bytes.len() / 2]).unwrap();
    let e = share_error(&short, 1..=1);
    assert!(e.contains(": byte "), "{e}");
    assert!(e.contains("unexpected end of file"), "{e}");
}

/// A file of a split set (Gmsh's `-part_split`: it declares every
/// partition and holds one) is refused for the partitions it does not
/// hold, with the advice to read the set.
#[test]
fn a_file_of_a_split_set_is_not_taken_for_the_whole() {
    let first = fixture_dir().join("channel_hole_split3_v41_ascii_1.msh");
    assert!(read_share(&first, 1..=1).is_ok());
    let e = share_error(&first, 1..=3);
    assert!(e.starts_with(&format!("{}:", first.display())), "{e}");
    let said = "no element of partition 2 of the 3 it declares is in this file";
    assert!(e.contains(said), "{e}");
    assert!(e.contains("read the set with --split"), "{e}");
}
