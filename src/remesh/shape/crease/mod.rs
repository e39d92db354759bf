//! Creases of the input kept by the remesh (ours, with `--creases keep`, and by default with
//! `--sizing curvature`; the paper pulls the
//! cap mesh back as is, Sec. 4.2): remesh vertices put on the input's sharp edges and joined
//! along them, as isotropic remeshers with feature edges do. See docs/method.md, "21. Creases".
//!
//! A crease is a chain of input edges whose two faces' normals differ by more than the crease
//! bound, also at the remesh's scale ([`detect`]'s `SCALE_SHARE`). The map is linear on each
//! input face, so an input edge goes onto the segment between its ends' planar points, and a
//! point at a fraction of the edge in the plane lifts to the same fraction of the edge on the
//! surface: a vertex put there lies exactly on the crease. Along each chain long enough at the remesh's
//! scale, points are spaced by about the remesh's edge length; the nearest free remesh vertex
//! of each travels onto it over the iterations (each move kept valid in the plane and on the
//! surface) and stays there, and edge flips join consecutive ones. The flips' crease bound then
//! keeps the joining edges; crease vertices of faces still thin at the end are freed.
//!
//! Three steps, one file each: [`detect`] finds the chains, [`snap`] places remesh vertices
//! on points along them, [`join`] joins consecutive points by edge flips.

mod detect;
mod grid;
mod join;
mod snap;

pub(crate) use detect::crease_chains;
pub(crate) use snap::{release_thin, CreaseSnap};
