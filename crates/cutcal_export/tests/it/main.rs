//! Integration tests of cutcal_export (one binary, style.md §10).

// Shared fixtures: the paper's materials, Table 5 JC sets, options.
mod common;
// Named insta snapshots of every dialect x material.
mod snapshots;
// dynars (third-party LS-DYNA parser) reads every deck back.
mod dynars_deck;
// CalculiX runs the tabular Abaqus card (single-element uniaxial tests).
mod calculix;
// Property tests: columns, render -> parse round trip, NaN/inf rejected.
mod roundtrip;
// The VFRICTION source compiled with gfortran and called with the documented argument order.
mod vfriction;
