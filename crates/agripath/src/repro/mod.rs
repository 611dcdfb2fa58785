//! The papers' tables, recomputed. Each function computes rows; the CLI prints them.

pub mod printed;
pub mod seed000_ablation;
pub mod seed000_table2;
pub mod seed001_table7;
pub mod seed001_table8;
pub mod seed003_table4;
pub mod seed004;
pub mod tracks;
