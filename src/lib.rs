#![doc = include_str!("../README.md")]

pub use shapegen_runtime::*;

pub mod scene;
