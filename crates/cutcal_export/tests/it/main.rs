//! Integration tests of cutcal_export (one binary, style.md §10).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

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
// The interpreter of the third-party Python readers (skip or fail when missing).
mod pytools;
// ansys-materials-manager's MatmlReader reads every MatML file (values compared).
mod ansys_matml;
// PyDyna parses every LS-DYNA deck; every referenced ID resolves.
mod pydyna;
// A JC set outside the literature box is flagged in every header.
mod literature;
// Complete 2-D decks per cutting test: snapshot, numbers, PyDyna.
mod deck2d;
