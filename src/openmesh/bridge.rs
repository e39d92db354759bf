//! The cxx bridge to the C++ shim `shim.cc`, which calls OpenMesh's reader and writer.

#[cxx::bridge(namespace = "capmesh_openmesh")]
pub(crate) mod ffi {
    unsafe extern "C++" {
        include!("capmesh/src/openmesh/shim.h");

        /// Read any format OpenMesh knows into flat arrays (polygons are triangulated).
        fn read_mesh(path: &str, positions: &mut Vec<f64>, triangles: &mut Vec<u32>) -> Result<()>;

        /// Write flat arrays (indices already checked) in the format of the path's extension.
        fn write_mesh(path: &str, positions: &[f64], triangles: &[u32], binary: bool) -> Result<()>;
    }
}
