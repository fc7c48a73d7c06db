use model_runtime::Model;
model_macros::model! {
    pub mod slip2 {
        params { m = 1.0 }
        states { u_X, u_Y }
        let v = sqrt(u_X^2 + u_Y^2);
        let al = atan2(-u_Y, -u_X);
        equations {
            along: -m*der(v) = 1;
            across: m*v*der(al) = 0;
        }
    }
}
#[test]
fn repro() {
    let m = slip2::Model::default();
    for y in [[0.0, 1.0], [1e-12, 1.0], [1e-8, 1.0], [0.6, 0.8]] {
        let mut dy = [0.0; 2];
        let r = m.rhs(0.0, &y, &mut dy);
        let v = (y[0] * y[0] + y[1] * y[1]).sqrt();
        println!("u = {y:?}: {r:?} dy = {dy:?}, exact = {:?}, pivots {:?}", [-y[0] / v, -y[1] / v], slip2::INFO.pivots);
    }
}
