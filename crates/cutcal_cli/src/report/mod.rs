//! Report building blocks: SVG plots and the plots of the DPZD identification.

pub mod plots;
pub mod svg;
