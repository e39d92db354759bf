//! Helpers shared by the integration tests (`mod common;` in each test file): the test
//! meshes, temporary directories and a deterministic random number generator here; running
//! the command line in `cli`, reading its CSV files in `csv`, calling the C ABI in `capi`.

// Each test binary uses some of these.
#![allow(dead_code)]

#[cfg(feature = "capi")]
pub mod capi;
pub mod cli;
pub mod csv;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A test mesh from tests/data (or its `.gz` copy, or the shared collection next to the
/// repository); the tests/data path when none exists, so that the error names it.
pub fn data(name: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = [
        root.join("tests/data").join(name),
        root.join("tests/data").join(format!("{name}.gz")),
        root.join("../shared/data/meshes").join(name),
    ];
    candidates.iter().find(|p| p.exists()).unwrap_or(&candidates[0]).clone()
}

/// The bundled closed `name` without the faces within `rings` edges of its lowest vertex: one
/// hole (5-6 boundary edges for `rings = 1`), as a segmentation cut by the volume's edge.
pub fn holed(name: &str, rings: usize) -> capmesh::TriMesh {
    let m = capmesh::io::read_mesh(&data(name)).unwrap();
    let lowest = (0..m.vertices.len()).min_by(|&a, &b| m.vertices[a][2].total_cmp(&m.vertices[b][2])).unwrap() as u32;
    let mut removed = vec![lowest];
    for _ in 1..rings {
        let ring: Vec<u32> = m.faces.iter().filter(|f| f.iter().any(|v| removed.contains(v))).flatten().copied().collect();
        removed.extend(ring);
        removed.sort_unstable();
        removed.dedup();
    }
    let faces = m.faces.iter().copied().filter(|f| !f.iter().any(|v| removed.contains(v))).collect();
    capmesh::TriMesh { vertices: m.vertices, faces }
}

/// A fresh, unique directory under the system temp dir, removed on drop. Derefs to its path.
pub struct TempDir(PathBuf);

impl TempDir {
    /// A new directory whose name starts with `capmesh-{tag}-`.
    pub fn new(tag: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_nanos()).unwrap_or(0);
        let dir = std::env::temp_dir().join(format!("capmesh-{tag}-{}-{}-{nanos}", std::process::id(), COUNTER.fetch_add(1, Ordering::Relaxed)));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    /// The path of `name` in this directory.
    pub fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// Write `bytes` to `name` in this directory and return the path.
    pub fn file(&self, name: &str, bytes: &[u8]) -> PathBuf {
        let path = self.path(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }
}

impl std::ops::Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A small deterministic generator (SplitMix64): the same sequence on every run and machine.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// A long bone of revolution about `x`: a shaft of radius 0.4 from `-half` to `half` with a
/// ball of radius 0.8 blended onto one end and of 0.64 onto the other (a femur's proportions
/// when `half` is about 8), as `rings` rings of `sectors` vertices evenly spaced in `x` and a
/// vertex at each tip.
pub fn long_bone(half: f64, rings: usize, sectors: usize) -> capmesh::TriMesh {
    let (shaft, end) = (0.4f64, 0.8f64);
    // The squared radius: the shaft's and each ball's, joined by a smooth maximum.
    let radius = |x: f64| {
        let k = 0.3 * shaft * shaft;
        let mut v = shaft * shaft;
        for e in [end * end - (x + half).powi(2), (0.8 * end).powi(2) - (x - half).powi(2)] {
            let h = (0.5 + 0.5 * (e - v) / k).clamp(0.0, 1.0);
            v = e * h + v * (1.0 - h) + k * h * (1.0 - h);
        }
        v.max(0.0).sqrt()
    };
    let (left, right) = (-(half + end), half + 0.8 * end);
    let mut vertices = vec![[left, 0.0, 0.0]];
    for i in 1..rings {
        let x = left + (right - left) * i as f64 / rings as f64;
        let r = radius(x);
        for j in 0..sectors {
            let t = std::f64::consts::TAU * j as f64 / sectors as f64;
            vertices.push([x, r * t.cos(), r * t.sin()]);
        }
    }
    vertices.push([right, 0.0, 0.0]);
    let at = |i: usize, j: usize| (1 + i * sectors + j % sectors) as u32;
    let tip = vertices.len() as u32 - 1;
    let mut faces = Vec::new();
    for j in 0..sectors {
        faces.push([0, at(0, j + 1), at(0, j)]);
        faces.push([tip, at(rings - 2, j), at(rings - 2, j + 1)]);
    }
    for i in 0..rings - 2 {
        for j in 0..sectors {
            faces.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
            faces.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
        }
    }
    capmesh::TriMesh::new(vertices, faces)
}
