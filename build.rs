//! Build script: with feature `openmesh`, compile the cxx bridge and the C++ shim in
//! src/openmesh/ and link OpenMesh (Debian: libopenmesh-dev). Set `OPENMESH_INCLUDE_DIR` and
//! `OPENMESH_LIB_DIR` for an OpenMesh outside the system paths. Nothing to do otherwise.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    #[cfg(feature = "openmesh")]
    openmesh();
}

#[cfg(feature = "openmesh")]
fn openmesh() {
    for f in ["src/openmesh/bridge.rs", "src/openmesh/shim.cc", "src/openmesh/shim.h"] {
        println!("cargo:rerun-if-changed={f}");
    }
    println!("cargo:rerun-if-env-changed=OPENMESH_INCLUDE_DIR");
    println!("cargo:rerun-if-env-changed=OPENMESH_LIB_DIR");
    let mut build = cxx_build::bridge("src/openmesh/bridge.rs");
    build.file("src/openmesh/shim.cc").std("c++17").warnings(false);
    if let Ok(dir) = std::env::var("OPENMESH_INCLUDE_DIR") {
        build.include(dir);
    }
    build.compile("capmesh_openmesh");
    if let Ok(dir) = std::env::var("OPENMESH_LIB_DIR") {
        println!("cargo:rustc-link-search=native={dir}");
    }
    println!("cargo:rustc-link-lib=OpenMeshCore");
}
