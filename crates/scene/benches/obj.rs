//! Criterion benchmark of OBJ loading: `load_obj` on the full Stanford bunny
//! (data/meshes/bunny.obj: 2.4 MB, 34 835 positions, 69 666 triangles, no normals, so the
//! area-weighted normals are computed too). The file is read from disk on every iteration (it stays
//! in the page cache), as a user's load would.

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{Criterion, criterion_group, criterion_main};
use shadowlab_scene::load_obj;

fn bunny(c: &mut Criterion) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes/bunny.obj");
    c.bench_function("load_obj bunny.obj (69 666 triangles)", |b| {
        b.iter(|| load_obj(black_box(&path)).expect("bunny.obj loads"));
    });
}

criterion_group!(benches, bunny);
criterion_main!(benches);
