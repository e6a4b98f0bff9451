//! Element quality, inversion check and the paper's histogram bins.
