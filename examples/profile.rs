use std::time::Instant;
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let t = Instant::now();
    let lesson = shadelab::lesson::load(path.as_ref(), &[]).unwrap();
    eprintln!("load {:?}", t.elapsed());
    let t = Instant::now();
    let scene = shadelab::scene::build::build(&lesson).unwrap();
    eprintln!("build {:?}", t.elapsed());
    for _ in 0..5 {
        let t = Instant::now();
        let (frame, _) = shadelab::render::render(&scene, &[shadelab::render::Layer::Total]);
        eprintln!("render {:?}", t.elapsed());
        let t = Instant::now();
        let px = frame.layer(shadelab::render::Layer::Total).unwrap();
        let rgb = shadelab::render::develop::develop(&px, 0.0, shadelab::render::Tonemap::Clamp);
        eprintln!("develop {:?}", t.elapsed());
        let t = Instant::now();
        let mut v = Vec::new();
        shadelab::output::encode_png(&mut v, frame.width, frame.height, &rgb).unwrap();
        eprintln!("png {:?}", t.elapsed());
    }
}
