#[path = "../benches/grid.rs"]
mod grid;
use grid::grid;
fn main() {
    let p = std::env::args().nth(1).unwrap();
    aster_mesh::write_med(std::path::Path::new(&p), &grid(1000), "GRID", &[]).unwrap();
}
