//! Points of the input or the remesh by position, for the crease steps' searches within one
//! remesh edge length (face centroids in [`super::detect`], free vertices in [`super::snap`]).

use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{norm, sub};

/// Numbered points in cubes of side `cell`, for the points within `cell` of a place.
pub(super) struct PointGrid {
    cell: f64,
    cubes: FastMap<[i64; 3], Vec<(u32, [f64; 3])>>,
}

impl PointGrid {
    pub(super) fn new(cell: f64, points: impl IntoIterator<Item = (u32, [f64; 3])>) -> Self {
        let mut cubes: FastMap<[i64; 3], Vec<(u32, [f64; 3])>> = FastMap::default();
        if cell > 0.0 {
            for (i, x) in points {
                cubes.entry(x.map(|c| (c / cell).floor() as i64)).or_default().push((i, x));
            }
        }
        Self { cell, cubes }
    }

    /// The points within `radius` (at most the cell) of `x` and their distances, cube by cube.
    pub(super) fn near(&self, x: [f64; 3], radius: f64) -> impl Iterator<Item = (u32, f64)> + '_ {
        let c = x.map(|v| (v / self.cell).floor() as i64);
        (0..27)
            .flat_map(move |k| {
                let key = [c[0] + k % 3 - 1, c[1] + (k / 3) % 3 - 1, c[2] + k / 9 - 1];
                self.cubes.get(&key).map_or(&[][..], |l| &l[..]).iter()
            })
            .map(move |&(i, y)| (i, norm(sub(y, x))))
            .filter(move |&(_, d)| d <= radius)
    }
}
