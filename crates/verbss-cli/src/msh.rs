//! `--msh-version`, `--binary`, `--ascii`: how a `.msh` output is written.
//! Without them a mesh read from a Gmsh file is written in that file's MSH
//! version and encoding, any other in MSH 4.1 ASCII.

use clap::{Args, ValueEnum};
use verbss::io::{MshVersion, WriteOptions};
use verbss::mesh::Mesh;

/// The `.msh` output options of `convert`, `deform` and `run`.
#[derive(Args, Clone, Default)]
pub struct MshArgs {
    /// MSH version of a .msh output [default: the input's, else 4.1].
    #[arg(long, value_enum)]
    msh_version: Option<MshVersionArg>,
    /// Write a .msh output binary [default: as the input, else ASCII].
    #[arg(long, conflicts_with = "ascii")]
    binary: bool,
    /// Write a .msh output as ASCII [default: as the input].
    #[arg(long)]
    ascii: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum MshVersionArg {
    #[value(name = "2.2")]
    V22,
    #[value(name = "4.1")]
    V41,
}

impl MshArgs {
    /// `options` with the version and encoding these arguments name.
    pub fn apply(&self, mut options: WriteOptions) -> WriteOptions {
        if let Some(v) = self.msh_version {
            options.msh_version = match v {
                MshVersionArg::V22 => MshVersion::V22,
                MshVersionArg::V41 => MshVersion::V41,
            };
        }
        if self.binary || self.ascii {
            options.binary = self.binary;
        }
        options
    }

    /// How the MSH 4.1 pieces of a split set are written: binary (`true`)
    /// or ASCII as these arguments say, `None` for as the input. A split
    /// set has partitioned entities, which MSH 2.2 has not: `--msh-version
    /// 2.2` fails.
    pub fn split_encoding(&self) -> anyhow::Result<Option<bool>> {
        if matches!(self.msh_version, Some(MshVersionArg::V22)) {
            anyhow::bail!(
                "--msh-version 2.2: MSH pieces are written as a split set of MSH 4.1 files \
                 (MSH 2.2 has no partitioned entities); give --msh-version 4.1, or a .pvtu output"
            );
        }
        Ok((self.binary || self.ascii).then_some(self.binary))
    }

    /// The options `mesh` is written with: as it was read
    /// ([`WriteOptions::for_mesh`]) unless these arguments say otherwise.
    pub fn options(&self, mesh: &Mesh) -> WriteOptions {
        self.apply(WriteOptions::for_mesh(mesh))
    }
}
