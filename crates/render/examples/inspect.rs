//! Prints the runs of hit pixels along one row of a data file with their emission times:
//! `cargo run -p render --example inspect -- DATA.exr [ROW]`.

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("usage: inspect DATA.exr [ROW]");
    let data = datafile::DataFile::read(std::path::Path::new(&path))
        .unwrap_or_else(|e| panic!("{e}"));
    let row: usize = args
        .next()
        .map_or(data.height / 2, |r| r.parse().expect("row"));
    let mut run: Option<(usize, i32, f32, f32)> = None;
    let mut runs = 0;
    for col in 0..=data.width {
        let r = (col < data.width).then(|| data.records[row * data.width + col]);
        let key = r.filter(|r| r.is_hit()).map(|r| (r.object, r.t_emit));
        match (&mut run, key) {
            (Some((_, o, t0, t1)), Some((ob, t))) if *o == ob && (t - *t1).abs() < 0.5 => {
                *t1 = t;
                let _ = t0;
            }
            _ => {
                if let Some((c0, o, t0, t1)) = run.take() {
                    runs += 1;
                    println!(
                        "cols {c0:4}..{:4} object {o} t_emit {t0:9.3} .. {t1:9.3}",
                        col - 1
                    );
                }
                if let Some((o, t)) = key {
                    run = Some((col, o, t, t));
                }
            }
        }
    }
    println!(
        "row {row}: {runs} images; whole image: {} images",
        count_images(&data)
    );
}

/// Images = 8-connected groups of hit pixels of one object with continuous emission time
/// (neighbours differing by less than 0.5 in t_emit).
#[allow(dead_code)]
pub fn count_images(data: &datafile::DataFile) -> usize {
    let (w, h) = (data.width, data.height);
    let mut label = vec![0usize; w * h];
    let mut n = 0;
    for start in 0..w * h {
        if label[start] != 0 || !data.records[start].is_hit() {
            continue;
        }
        n += 1;
        label[start] = n;
        let mut stack = vec![start];
        while let Some(i) = stack.pop() {
            let (c, r) = ((i % w) as i64, (i / w) as i64);
            for dr in -1..=1 {
                for dc in -1..=1 {
                    let (cc, rr) = (c + dc, r + dr);
                    if cc < 0 || rr < 0 || cc >= w as i64 || rr >= h as i64 {
                        continue;
                    }
                    let j = rr as usize * w + cc as usize;
                    let (a, b) = (data.records[i], data.records[j]);
                    if label[j] == 0
                        && b.is_hit()
                        && a.object == b.object
                        && (a.t_emit - b.t_emit).abs() < 0.5
                    {
                        label[j] = n;
                        stack.push(j);
                    }
                }
            }
        }
    }
    n
}
