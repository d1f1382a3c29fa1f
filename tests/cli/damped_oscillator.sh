# Sourced by the fit and sweep tests: write_damped_oscillator DIR writes DIR/oscillator.toml, the
# damped oscillator x'' + 2 zeta w x' + w^2 x = 0 as an equation case file (starting from
# w = 1.2, zeta = 0.08; v at the true -zeta w), and DIR/oscillator.csv, exact samples of its
# solution at w = 1, zeta = 0.05 from x(0) = 1, x'(0) = -zeta w: x = exp(-zeta w t) cos(w_d t),
# w_d = w sqrt(1 - zeta^2), at t = 0 .. 20 by 0.1.
write_damped_oscillator() {
  cat > "$1/oscillator.toml" <<'TOML'
kind = "equations"
[states]
x = 1.0
v = -0.05
[parameters]
w = { value = 1.2, min = 0.0 }
zeta = { value = 0.08, min = 0.0 }
[equations]
x = "v"
v = "-2*zeta*w*v - w^2*x"
TOML
  /usr/bin/python3 -c "
import math
w, z = 1.0, 0.05
wd = w * math.sqrt(1 - z * z)
print('t,x')
for k in range(201):
    t = 0.1 * k
    print('%r,%r' % (t, math.exp(-z * w * t) * math.cos(wd * t)))" > "$1/oscillator.csv"
}
