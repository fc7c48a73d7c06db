pub mod dp {
    params { m1 = 0.0, m2 = 0.7, l1 = 1.0, l2 = 0.6, g = 9.81 }
    states { th1, th2, om1, om2 }
    let d = th1 - th2;
    equations {
        der(th1) = om1;
        der(th2) = om2;
        (m1 + m2)*l1^2*der(om1) + m2*l1*l2*cos(d)*der(om2) = -m2*l1*l2*sin(d)*om2^2 - (m1 + m2)*g*l1*sin(th1);
        m2*l1*l2*cos(d)*der(om1) + m2*l2^2*der(om2) = m2*l1*l2*sin(d)*om1^2 - m2*g*l2*sin(th2);
    }
    outputs { energy = (m1 + m2)/2*l1^2*om1^2 + m2/2*l2^2*om2^2 + m2*l1*l2*om1*om2*cos(d); }
}
