#![doc = include_str!("../README.md")]

// The command-line tool names this crate as its users do.
extern crate self as shapegen;

pub use shapegen_runtime::*;

#[cfg(feature = "cli")]
pub mod cli;
pub mod registry;
pub mod scene;
pub mod search;
