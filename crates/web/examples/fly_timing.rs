//! The native time of the page's flight: `fly_timing MISSION [REPEATS]` gives the mission
//! and every other file of its folder to [`karman_web::fly`], the very function the page
//! calls, REPEATS times (default 5), and prints the fastest in milliseconds. The browser test
//! compares it with the page's time of the same call.

use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let mission =
        std::path::PathBuf::from(args.next().ok_or("usage: fly_timing MISSION [REPEATS]")?);
    let repeats: u32 = args.next().map_or(Ok(5), |r| r.parse())?;
    let dir = mission.parent().ok_or("the mission has no folder")?;
    let mut files = karman_web::Files::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_file() && path != mission {
            let name = path.file_name().ok_or("a file without a name")?;
            files.add(&name.to_string_lossy(), std::fs::read(&path)?)?;
        }
    }
    let text = std::fs::read_to_string(&mission)?;
    let name = mission.file_name().ok_or("no file name")?.to_string_lossy();
    let mut fastest = f64::INFINITY;
    for _ in 0..repeats.max(1) {
        let started = Instant::now();
        karman_web::fly(&name, &text, &files)?;
        fastest = fastest.min(started.elapsed().as_secs_f64() * 1e3);
    }
    println!("{fastest}");
    Ok(())
}
