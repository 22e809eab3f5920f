//! The constraint graph (Box2D's `constraint_graph.c`): graph colouring, in one place.
//!
//! Within a colour no two constraints share a body the solver moves, so a colour's
//! constraints can be solved in any order, several at a time in SIMD lanes or on several
//! threads, with the same result as one by one. Soft step solves colour by colour; the classic
//! solvers, and soft step with colouring off, take the contacts one by one instead.
//!
//! - [`colors`]: the persistent colouring of the touching contacts, kept as they start and
//!   stop touching, so a step spends nothing on it.
//! - [`layout`]: where each colour's contacts sit in the contact array, so the solver reads a
//!   colour in memory order.
//! - [`order`]: one step's solve order, colour by colour then the overflow, with the
//!   colouring's promise checked before the solver writes bodies in place on its strength.
//! - [`joints`]: the joints, coloured afresh each step (and why not persistently).

pub(crate) mod colors;
pub(crate) mod joints;
pub(crate) mod layout;
pub(crate) mod order;
