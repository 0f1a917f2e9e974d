//! Print one line per mesh file: name, summary JSON, coordinate sum and
//! connectivity sum — for cross-checking readers against other tools.

fn main() {
    for arg in std::env::args().skip(1) {
        let path = std::path::Path::new(&arg);
        match aster_mesh::read_mesh(path) {
            Ok(m) => {
                let csum: f64 = m.coords.iter().map(|c| c[0] + c[1] + c[2]).sum();
                let nsum: u64 = m
                    .cells
                    .iter()
                    .flat_map(|c| c.nodes.iter())
                    .map(|n| n.0 as u64 + 1)
                    .sum();
                let s = serde_json::to_string(&m.summary()).unwrap_or_default();
                println!("{arg}\t{s}\t{csum:.6e}\t{nsum}");
            }
            Err(e) => println!("{arg}\tERROR\t{e}"),
        }
    }
}
