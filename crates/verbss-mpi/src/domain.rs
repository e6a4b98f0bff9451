//! A rank's share of a mesh as the domain of the one engine
//! ([`verbss::deform::Deformer::on`]): its part with the ghost layer as the
//! deformer's local mesh (every cell around its owned nodes, every group's
//! facets around them), the ranks as its [`Collective`](verbss::collective::Collective)
//! ([`Ranks`]), and the part's colour-by-colour sweeps as its spring solver
//! ([`LocalSolver`]). No rank holds the whole mesh.

use std::sync::Arc;

use verbss::deform::{Deformer, Domain};
use verbss::mesh::FileOrigin;
use verbss::motion::{Attachment, Numbering};
use verbss::settings::Settings;
use verbss::solve::{SolveInfo, SolveParams, SpringSolver};
use verbss::{Mesh, Result};

use crate::coupled::LocalSolver;
use crate::ghosts::Ghosts;
use crate::ranks::Ranks;
use crate::Comm;

/// A mesh in motion over the ranks, each holding its part.
pub type PartDeformer<'c> = Deformer<LocalSolver<'c>, Ranks<'c>>;

/// A rank's part, ready to become a deformer's domain.
pub struct PartDomain<'c> {
    comm: &'c Comm,
    ghosts: Ghosts,
    /// The part as a mesh: its nodes (owned and ghosts), cells and groups.
    pub mesh: Arc<Mesh>,
    /// The whole mesh's node count.
    total: usize,
}

impl<'c> PartDomain<'c> {
    /// The part of this rank's `share` of a mesh, its node `i` numbered
    /// `global[i]` (the same on every rank holding it), with every group of
    /// `groups` (every rank the same names, in the same order; collective).
    pub fn new(
        comm: &'c Comm,
        share: &Mesh,
        global: &[u64],
        groups: &[String],
    ) -> Result<PartDomain<'c>> {
        let ghosts = Ghosts::new(comm, share, global)?;
        let coords = ghosts.spread(comm, &share.coords, share.dim);
        let groups = ghosts.groups(comm, share, groups)?;
        let part = &ghosts.part;
        let mesh = Mesh {
            dim: share.dim,
            coords,
            node_tags: part.node_tags.clone(),
            cells: part.cells.clone(),
            cell_tags: part.cell_tags.clone(),
            groups,
            origin: FileOrigin::default(),
        };
        let owned = part.owner.iter().filter(|&&o| o == part.rank).count();
        Ok(PartDomain {
            total: comm.sum(owned as u64) as usize,
            comm,
            ghosts,
            mesh: Arc::new(mesh),
        })
    }

    /// How the part's nodes are numbered in a positions file: their global
    /// numbers.
    pub fn numbering(&self) -> Numbering {
        let part = &self.ghosts.part;
        Numbering {
            global: part.global.clone(),
            owned: (0..part.node_count()).map(|i| part.owns(i)).collect(),
            total: Some(self.total),
        }
    }

    /// The share's node `i`'s index in the part.
    pub fn local(&self) -> &[usize] {
        &self.ghosts.local
    }

    /// The deformer of this part (collective): `attachments` and
    /// `settings` as one process's, the springs solved over the ranks.
    pub fn deformer(
        self,
        attachments: &[Attachment],
        settings: Settings,
    ) -> Result<PartDeformer<'c>> {
        let PartDomain {
            comm, ghosts, mesh, ..
        } = self;
        let domain = Domain {
            global: ghosts.part.global.clone(),
            on: Ranks::new(comm, ghosts.part.owner.clone(), ghosts.halo.clone()),
            mesh,
        };
        let identity = Ghosts {
            local: (0..ghosts.part.node_count()).collect(),
            ..ghosts
        };
        Deformer::on(domain, attachments, settings, |setup| {
            let mut solver = LocalSolver::with_ghosts(comm, identity, setup.roles, setup.normals)?;
            solver.set_stiffness(setup.stiffness)?;
            Ok(solver)
        })
    }
}

impl SpringSolver for LocalSolver<'_> {
    fn solve(&mut self, coords: &[f64], u: &mut [f64], params: &SolveParams) -> Result<SolveInfo> {
        LocalSolver::solve(self, coords, u, params)
    }

    fn solve_exact(
        &mut self,
        coords: &[f64],
        u: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        LocalSolver::solve_exact(self, coords, u, params)
    }
}
