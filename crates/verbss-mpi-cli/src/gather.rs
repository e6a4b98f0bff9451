//! `--gather FILE.vtu` of a run on shares: rank 0 writes the whole moved
//! mesh as one ASCII `.vtu`, receiving the other ranks' data in messages of
//! at most [`CHUNK`] numbers, so that it never holds more than its own
//! share and one message.
//!
//! Every node is written once, by its owner (the lowest rank holding it,
//! [`Part::owner`]): the points are rank 0's owned nodes, then rank 1's,
//! and so on, each rank's in its share's order. A cell is written by the
//! one rank whose share holds it, its nodes as positions in that list: a
//! rank knows the positions of its owned nodes (its first position is the
//! number of nodes the lower ranks own) and asks the others of the owners
//! through a directory (node `g` at rank `g mod P`; two all-to-all
//! exchanges). The file holds the volume cells, point data `node_tag` and
//! cell data `cell_tag` (the input's numbers), and no boundary group.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::Context;
use verbss::io::gmsh::partitioned::Share;
use verbss::io::temp_path;
use verbss::Mesh;
use verbss_mpi::directory;
use verbss_mpi::part::Part;
use verbss_mpi::share::global_numbers;
use verbss_mpi::Comm;

/// The most numbers in one message to rank 0.
pub const CHUNK: usize = 1 << 16;

/// The largest tag that travels exactly as a double, `2^53`; positions in
/// the file are below the node count, far below it.
const EXACT: u64 = 1 << 53;

/// Fails on every rank when a node or cell tag of any rank's `mesh` is
/// above 2^53, which would not travel exactly (collective; `path` the
/// `--gather` file, for the message).
pub fn check_tags(world: &Comm, path: &Path, mesh: &Mesh) -> anyhow::Result<()> {
    let exact = |t: &u64| *t <= EXACT;
    let inexact = !(mesh.node_tags.iter().all(exact) && mesh.cell_tags.iter().all(exact));
    if world.sum(u64::from(inexact)) > 0 {
        anyhow::bail!(
            "--gather {}: a node or cell tag above 2^53 cannot be gathered (the numbers \
             travel as doubles)",
            path.display()
        );
    }
    Ok(())
}

/// Writes every rank's `share` at its nodes' `coords` as one `.vtu` at
/// `path` on rank 0 (collective; `part` is this rank's part with the ghost
/// layer, for the owners; its tags passed [`check_tags`]). Every rank
/// learns of a failure to write.
pub fn gather(
    world: &Comm,
    path: &Path,
    share: &Share,
    part: &Part,
    coords: &[f64],
) -> anyhow::Result<()> {
    let mesh = &share.mesh;
    let dim = mesh.dim;
    let global = global_numbers(share);
    let owned: Vec<bool> = global
        .iter()
        .map(|g| {
            let k = part
                .global
                .binary_search(g)
                .expect("a share node is in the part");
            part.owner[k] == part.rank
        })
        .collect();
    let owned_count = owned.iter().filter(|&&o| o).count();
    let counts = world.all_gather(&[
        owned_count as u64,
        mesh.cell_count() as u64,
        mesh.cells.iter().map(|(_, n)| n.len() as u64).sum::<u64>(),
    ]);
    let rank = world.rank() as usize;
    let before = |k: usize| counts[..rank].iter().map(|c| c[k]).sum::<u64>();
    let position = positions(world, &global, &owned, before(0));
    let mut points = Vec::with_capacity(3 * owned_count);
    let mut node_tags = Vec::with_capacity(owned_count);
    for (i, _) in owned.iter().enumerate().filter(|(_, &o)| o) {
        for d in 0..3 {
            points.push(if d < dim { coords[dim * i + d] } else { 0.0 });
        }
        node_tags.push(mesh.node_tags[i] as f64);
    }
    let mut connectivity = Vec::new();
    let mut offsets = Vec::with_capacity(mesh.cell_count());
    let mut end = before(2);
    for (kind, nodes) in mesh.cells.iter() {
        connectivity.extend((0..nodes.len()).map(|i| position[nodes[kind.vtk_local(i)]] as f64));
        end += nodes.len() as u64;
        offsets.push(end as f64);
    }
    let types: Vec<f64> = mesh
        .cells
        .kinds
        .iter()
        .map(|k| f64::from(k.vtk_id()))
        .collect();
    let cell_tags: Vec<f64> = mesh.cell_tags.iter().map(|&t| t as f64).collect();
    let total = |k: usize| counts.iter().map(|c| c[k]).sum::<u64>();
    let mut file = rank_zero_file(world, path, total(0), total(1))?;
    let arrays: [(&str, &str, usize, &[f64]); 6] = [
        ("Float64", "Points", 3, &points),
        ("Int64", "connectivity", 1, &connectivity),
        ("Int64", "offsets", 1, &offsets),
        ("UInt8", "types", 1, &types),
        ("Int64", "node_tag", 1, &node_tags),
        ("Int64", "cell_tag", 1, &cell_tags),
    ];
    for (k, (kind, name, components, values)) in arrays.into_iter().enumerate() {
        let opening = match k {
            0 => "      <Points>\n",
            1 => "      </Points>\n      <Cells>\n",
            4 => "      </Cells>\n      <PointData>\n",
            5 => "      </PointData>\n      <CellData>\n",
            _ => "",
        };
        file.text(opening);
        file.text(&format!(
            r#"        <DataArray type="{kind}" Name="{name}" NumberOfComponents="{components}" format="ascii">"#
        ));
        stream(world, values, |chunk| {
            file.numbers(chunk, kind == "Float64")
        });
        file.text("\n        </DataArray>\n");
    }
    file.text("      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    let written = file.finish();
    let failed = world.sum(u64::from(written.is_err()));
    written?;
    if failed > 0 {
        anyhow::bail!("rank 0 could not write {}", path.display());
    }
    Ok(())
}

/// The position in the gathered file of each node of the share (`global`
/// its global numbers, `owned` whether this rank owns it, `first` the
/// position of its first owned node), owned or not (collective: each owner
/// posts its nodes' positions to their [`directory`] ranks, which answer
/// the other holders).
fn positions(world: &Comm, global: &[u64], owned: &[bool], first: u64) -> Vec<u64> {
    let size = world.size() as u64;
    let mut position = vec![u64::MAX; global.len()];
    let mut posts = vec![Vec::new(); size as usize];
    let owned_nodes = global.iter().enumerate().filter(|&(i, _)| owned[i]);
    for (next, (i, &g)) in (first..).zip(owned_nodes) {
        position[i] = next;
        posts[(g % size) as usize].extend([g, next]);
    }
    let mut posted: Vec<(u64, u64)> = world
        .all_to_all(&posts)
        .iter()
        .flat_map(|list| list.chunks(2).map(|p| (p[0], p[1])))
        .collect();
    posted.sort_unstable();
    let others: Vec<usize> = (0..global.len()).filter(|&i| !owned[i]).collect();
    let asked: Vec<u64> = others.iter().map(|&i| global[i]).collect();
    let answers = directory::ask(world, &asked, |g| {
        let k = posted.binary_search_by_key(&g, |p| p.0);
        vec![posted[k.expect("every node has an owner")].1]
    });
    for (&i, answer) in others.iter().zip(answers) {
        position[i] = answer[0];
    }
    position
}

/// Every rank's `values` to rank 0 in rank order, in messages of at most
/// [`CHUNK`] numbers; rank 0 hands each to `write` as it comes
/// (collective).
fn stream(world: &Comm, values: &[f64], mut write: impl FnMut(&[f64])) {
    let lengths = world.all_gather(&[values.len() as u64]);
    if world.rank() != 0 {
        for chunk in values.chunks(CHUNK) {
            world.exchange(&[0], &[chunk.to_vec()], &mut [Vec::new()]);
        }
        return;
    }
    values.chunks(CHUNK).for_each(&mut write);
    for (r, length) in lengths.iter().enumerate().skip(1) {
        let mut left = length[0] as usize;
        while left > 0 {
            let mut chunk = [vec![0.0; left.min(CHUNK)]];
            world.exchange(&[r as i32], &[Vec::new()], &mut chunk);
            write(&chunk[0]);
            left -= chunk[0].len();
        }
    }
}

/// The file rank 0 writes, into a temporary file beside it renamed when
/// complete (nothing on the other ranks); after the first error the rest
/// is skipped, so that rank 0 still takes part in every exchange.
struct RankZeroFile {
    out: Option<BufWriter<File>>,
    temp: PathBuf,
    path: PathBuf,
    error: Option<std::io::Error>,
}

/// Opens the gathered file on rank 0 with its header for `points` points
/// and `cells` cells (collective: every rank fails when rank 0 cannot
/// create it).
fn rank_zero_file(
    world: &Comm,
    path: &Path,
    points: u64,
    cells: u64,
) -> anyhow::Result<RankZeroFile> {
    let temp = temp_path(path);
    let created = if world.rank() == 0 {
        File::create(&temp).map(|f| Some(BufWriter::new(f)))
    } else {
        Ok(None)
    };
    let failed = world.sum(u64::from(created.is_err()));
    let out = created.with_context(|| format!("cannot write {}", path.display()))?;
    if failed > 0 {
        anyhow::bail!("rank 0 cannot write {}", path.display());
    }
    let mut file = RankZeroFile {
        out,
        temp,
        path: path.to_path_buf(),
        error: None,
    };
    file.text(&format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
         byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    \
         <Piece NumberOfPoints=\"{points}\" NumberOfCells=\"{cells}\">\n"
    ));
    Ok(file)
}

impl RankZeroFile {
    /// Writes `text`.
    fn text(&mut self, text: &str) {
        self.put(|w| w.write_all(text.as_bytes()));
    }

    /// Writes `values`, each after a space: as floats (the shortest
    /// decimal that reads back to the same number) or as integers.
    fn numbers(&mut self, values: &[f64], float: bool) {
        self.put(|w| {
            for &v in values {
                if float {
                    write!(w, " {v}")?;
                } else {
                    write!(w, " {}", v as i64)?;
                }
            }
            Ok(())
        });
    }

    fn put(&mut self, f: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>) {
        if let (Some(w), None) = (self.out.as_mut(), &self.error) {
            self.error = f(w).err();
        }
    }

    /// Flushes and renames the file into place (rank 0), or says why not.
    fn finish(self) -> anyhow::Result<()> {
        let Some(mut w) = self.out else {
            return Ok(());
        };
        let flushed = match self.error {
            Some(e) => Err(e),
            None => w.flush(),
        };
        drop(w);
        let done = flushed.and_then(|()| std::fs::rename(&self.temp, &self.path));
        if done.is_err() {
            // The temporary file is of no use once the write failed.
            let _ = std::fs::remove_file(&self.temp);
        }
        done.with_context(|| format!("cannot write {}", self.path.display()))
    }
}
