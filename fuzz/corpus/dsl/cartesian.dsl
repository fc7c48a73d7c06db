mod m {
    params { m = 1.5, g = 9.81 }
    states { x, y, vx, vy, P }
    equations {
        kx: der(x) = vx;
        ky: der(y) = vy;
        mx: m*der(vx) = -der(P)*x;
        my: m*der(vy) = -der(P)*y - m*g;
        c: der(x*vx + y*vy) = 0;
    }
    outputs { lambda = der(P); energy = m/2*(vx^2 + vy^2) + m*g*y; }
}
