mod common;
use model_runtime::Model;
#[test]
fn look() {
    let p = equations::DiskParams::paper();
    let mut rng = common::Rng::new(3);
    for _ in 0..3 {
        let y = common::rolling_state(&mut rng, &p, common::Reach::Typical);
        let mut dy = [0.0; 12];
        equations::reference::RollingReference::new(p).unwrap().rhs(0.0, &y, &mut dy).unwrap();
        let e = common::explicit::rolling::<f64>(&p, &y).dy;
        let s = common::scales::rolling(&p, &y, &e);
        for i in 3..12 { println!("{i}: ref {:e} ex {:e} scale {:e}", dy[i], e[i], s[i]); }
    }
}
