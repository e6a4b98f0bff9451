//! The `verbss` command-line tool.

fn main() {}
