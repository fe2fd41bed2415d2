#!/usr/bin/env python3
# Independent on purpose: a test oracle (tests/cli/sliding_reference_test.py) in other equations; it never calls coinroll.
"""Independent reference for a coin that rolls and slides: Newton-Euler in world vectors.

Not the project's formulations (seed Euler angles, docs/derivations.md; material-frame quaternion,
docs/quaternion_formulation.md): the floor's reaction R at the contact is eliminated through the contact's
Delassus operator W (docs/sliding.md eqs. 1.9-1.10), every vector is in the floor frame, the centre of
mass's full 3D position and velocity are integrated (the height is checked against the contact, not
imposed). Pure Python (no numpy/scipy), deterministic: the same parameters give the same bytes.

Usage
    python3 tests/oracles/sliding_reference.py '{"mass": 0.00567, "radius": 0.01213, "mu": 0.3, "theta": 0.3,
        "omega_Y": -5.263469899354806, "omega_Z": -30, "v_x": 0.3, "v_z": 0.05, "duration": 1.0,
        "sample_dt": 0.01}'  >  run.csv
    (a steady circle, omega_Y from docs/rim.md 5.1, whose centre is launched off its rolling velocity
    (0.3639, 0) m/s: it skids for 0.0119 s, then rolls)
    python3 tests/oracles/sliding_reference.py @params.json [--extra]
    python3 tests/oracles/sliding_reference.py --self-test

Parameters (JSON object; SI units, ANGLES IN RADIANS, unlike the scene file's degrees):
    mass M (kg), radius a (m)                        required
    thickness h (m, default 0: the seed's thin coin), edge_radius rho (m, default h/2)
    I_X, I_Z (kg m^2)                                default: thin uniform disk M a^2/4, M a^2/2 (h = 0 only;
                                                     required when h > 0)
    g (m/s^2, default 9.81)
    mu       kinetic friction coefficient, required ("friction" in the scene)
    mu_s     static coefficient, >= mu, default mu ("friction_static")
    theta, phi, psi                                  initial Euler angles, rad (default 0)
    omega_X, omega_Y, omega_Z                        initial angular velocity in the seed's frame XYZ, rad/s
    x, z                                             initial centre of mass on the floor plane, m (default 0)
    v_x, v_z                                         initial centre-of-mass velocity, m/s; both absent (or a slip
                                                     below 1e-15 of the speed scale): the rolling velocity
                                                     v = -omega x c, the coin starts rolling (sliding at once if
                                                     the rolling reaction is outside the cone)
    duration (s, required), sample_dt (s, default 0.01), rtol, atol (default 1e-12 each)

Output: CSV on stdout, header exactly
    t,theta,omega_X,omega_Y,omega_Z,x,z,v_x,v_z,energy,slip_speed,sliding
(--extra appends phi,psi,y,v_y,normal_force,friction_force,dissipated,drift_height). Rows at t = k sample_dt,
k = 0 .. floor(duration / sample_dt), from the integrator's dense output; the rows stop where a terminating event
ends the run: lift-off (N falls through 0), painleve (D falls through 0 while sliding), corner-switch (a cornered
rim reaches upright), coin-flat (90 deg - |theta| < 0.5 deg). Numbers printed with repr (17 significant digits).
A sliding row's slip_speed is |s|; a rolling row's is 0. Exit codes: 0 done (also when an event ended the run),
2 bad parameters, 1 the integration failed.
Stderr: each switch ("sliding_reference: slides at t = ...", "... rolls at t = ..."), the end, and checks
of the held contact (height and vertical slip drift, |q| - 1, slip while rolling, energy balance).

Conventions (docs/seed.md §2, docs/derivations.md, docs/rim.md):
  - Floor frame xyz, y up; the floor is the plane y = 0. World vectors are in xyz.
  - Attitude: the unit quaternion q = q_y(phi) q_x(theta) q_z(psi), q_n(a) = cos(a/2) + n sin(a/2), an active
    rotation taking the floor axes to the coin's material axes b1, b2, b3 (b3 = e_Z, the symmetry axis).
  - Seed frame XYZ (not material): e_Z = R(q) z = (cos th sin ph, -sin th, cos th cos ph);
    e_X = y x e_Z / |y x e_Z| = (cos ph, 0, -sin ph), horizontal; e_Y = e_Z x e_X = (sin th sin ph, cos th,
    sin th cos ph), in the coin plane, up, from the contact towards the centre. At psi = 0, b1, b2, b3 = e_X, e_Y, e_Z.
  - theta is the tilt from vertical: sin theta = -e_Z . y; theta > 0 leans e_Z towards the floor. Reported as
    atan2(-e_Z . y, |e_Z horizontal|), in (-pi/2, pi/2). phi = atan2(e_Z,x, e_Z,z); psi from the material
    components u of y: atan2(u_1, u_2), unwrapped between rows.
  - omega is the world angular velocity; omega_X, omega_Y, omega_Z = omega . e_X, omega . e_Y, omega . e_Z
    (input and output), the seed's components.
  - Contact vector from G to the contact (docs/rim.md eq. 1.3):
        c = -(a - rho) e_Y + sigma (h/2 - rho) e_Z - rho y,   sigma = sign(theta)
    (h/2 - rho = 0 for a thin or fully rounded rim; a cornered rim may not pass upright: event corner-switch).
  - Inertia about G: I_G x = I_X x + (I_Z - I_X)(e_Z . x) e_Z.
  - Energy E = M |v_G|^2 / 2 + omega . I_G omega / 2 + M g y_G, with y_G, v_G the integrated values.

Model (docs/sliding.md): the contact is held (y . (v_G + omega x c) = 0, N >= 0). With the material contact
point's acceleration s_P' = W R + b,
    W x = x / M + (I_G^-1 (c x x)) x c,   b = -g y + (I_G^-1 (-omega x I_G omega)) x c + omega x c-dot,
rolling solves W R = -b (all three components of s_P' zero); sliding takes R = N (y - mu s_hat), s_hat the unit
horizontal slip s = v_G + omega x c, and N = -(y . b) / (y . W (y - mu s_hat)) (vertical part zero);
D = M y . W (y - mu s_hat) is the Painleve scalar. Then M a_G = R - M g y, I_G omega-dot = c x R - omega x I_G omega,
q-dot = (0, omega) q / 2. The work of friction mu N |s| is integrated as a 14th state ("dissipated").

Switching (docs/sliding.md §4):
  - rolling -> sliding where mu_s N - |F_roll| falls through 0 (root on the dense output); the slip is then 0 and
    the contract's direction is s_hat = -F_roll / |F_roll|. If |F_roll| > mu N there (mu < mu_s, or a rolling start
    outside the cone) the slip grows linearly; the run starts sliding from s = 0 in the self-consistent direction
    (4.9) nearest to -F_roll (equal to it when F_roll lies along e_X or h, or W_c is isotropic; off by (4.10) to first
    order in mu_s - mu otherwise). If mu = mu_s the slip grows quadratically along -F_roll (4.7): a seed interval of
    t0 = 1e-3 min(1 / max(|omega|, sqrt(g/a)), mu N / kappa) (printed on stderr) is integrated with the friction
    direction prescribed to first order in time, -F_roll/|F_roll| turned at the rate d of (4.8) (error O(t0^3) in
    the velocities, ~1e-11 m/s), after which the slip's own direction takes over (stiff while |s| is small: many
    short steps, §4.4).
  - sliding -> rolling where the slip speed reaches 0: each step is capped at the slip's linear time to zero and a
    step that reverses the slip is retried onto that time, until |s| <= s_snap = max(1e-12 V, 10 (atol + rtol V)),
    V the initial speed scale max(|v_G|, a |omega|, sqrt(g a)) (just above the integration's own noise); the last
    |s| / |ds/dt| of motion is then applied as one Euler increment and the residue of the slip zeroed. The coin rolls
    if the rolling reaction fits the cone |F_roll| <= mu_s N, else slides on in the self-consistent direction (4.9).
Integrator: DOP853 (Hairer, Norsett & Wanner; coefficients as published) with its 7th-order dense output,
error per step <= atol + rtol |y| in the RMS norm over all 14 states.
"""
import json
import math
import sys

# ------------------------------------------------------------------------------------------- vectors
Y_HAT = (0.0, 1.0, 0.0)


def add(u, v):
    return (u[0] + v[0], u[1] + v[1], u[2] + v[2])


def sub(u, v):
    return (u[0] - v[0], u[1] - v[1], u[2] - v[2])


def scale(s, u):
    return (s * u[0], s * u[1], s * u[2])


def dot(u, v):
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def cross(u, v):
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def norm(u):
    return math.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])


def solve3(cols, rhs):
    """Solve [c0 c1 c2] x = rhs by Cramer's rule (W is symmetric positive definite, well conditioned)."""
    c0, c1, c2 = cols
    det = dot(c0, cross(c1, c2))
    return (dot(rhs, cross(c1, c2)) / det, dot(c0, cross(rhs, c2)) / det, dot(c0, cross(c1, rhs)) / det)


def quat_mul(p, q):
    pw, px, py, pz = p
    qw, qx, qy, qz = q
    return (pw * qw - px * qx - py * qy - pz * qz,
            pw * qx + px * qw + py * qz - pz * qy,
            pw * qy - px * qz + py * qw + pz * qx,
            pw * qz + px * qy - py * qx + pz * qw)


def quat_rotate(q, v):
    """R(q) v for a unit quaternion q = (w, x, y, z)."""
    w, qv = q[0], (q[1], q[2], q[3])
    t = scale(2.0, cross(qv, v))
    return add(add(v, scale(w, t)), cross(qv, t))


def quat_from_euler(theta, phi, psi):
    """q = q_y(phi) q_x(theta) q_z(psi) (docs/seed.md §2)."""
    qy = (math.cos(phi / 2), 0.0, math.sin(phi / 2), 0.0)
    qx = (math.cos(theta / 2), math.sin(theta / 2), 0.0, 0.0)
    qz = (math.cos(psi / 2), 0.0, 0.0, math.sin(psi / 2))
    return quat_mul(quat_mul(qy, qx), qz)


# ------------------------------------------------------------------------------------------- DOP853
_C = { 2: 0.526001519587677318785587544488e-01, 3: 0.789002279381515978178381316732e-01, 4: 0.118350341907227396726757197510e+00, 5: 0.281649658092772603273242802490e+00, 6: 0.333333333333333333333333333333e+00, 7: 0.25e+00, 8: 0.307692307692307692307692307692e+00, 9: 0.651282051282051282051282051282e+00, 10: 0.6e+00, 11: 0.857142857142857142857142857142e+00, 14: 0.1e+00, 15: 0.2e+00, 16: 0.777777777777777777777777777778e+00 }
_A = {
    2: ((1, 5.26001519587677318785587544488e-2),),
    3: ((1, 1.97250569845378994544595329183e-2), (2, 5.91751709536136983633785987549e-2)),
    4: ((1, 2.95875854768068491816892993775e-2), (3, 8.87627564304205475450678981324e-2)),
    5: ((1, 2.41365134159266685502369798665e-1), (3, -8.84549479328286085344864962717e-1), (4, 9.24834003261792003115737966543e-1)),
    6: ((1, 3.7037037037037037037037037037e-2), (4, 1.70828608729473871279604482173e-1), (5, 1.25467687566822425016691814123e-1)),
    7: ((1, 3.7109375e-2), (4, 1.70252211019544039314978060272e-1), (5, 6.02165389804559606850219397283e-2), (6, -1.7578125e-2)),
    8: ((1, 3.70920001185047927108779319836e-2), (4, 1.70383925712239993810214054705e-1), (5, 1.07262030446373284651809199168e-1), (6, -1.53194377486244017527936158236e-2), (7, 8.27378916381402288758473766002e-3)),
    9: ((1, 6.24110958716075717114429577812e-1), (4, -3.36089262944694129406857109825e0), (5, -8.68219346841726006818189891453e-1), (6, 2.75920996994467083049415600797e1), (7, 2.01540675504778934086186788979e1), (8, -4.34898841810699588477366255144e1)),
    10: ((1, 4.77662536438264365890433908527e-1), (4, -2.48811461997166764192642586468e0), (5, -5.90290826836842996371446475743e-1), (6, 2.12300514481811942347288949897e1), (7, 1.52792336328824235832596922938e1), (8, -3.32882109689848629194453265587e1), (9, -2.03312017085086261358222928593e-2)),
    11: ((1, -9.3714243008598732571704021658e-1), (4, 5.18637242884406370830023853209e0), (5, 1.09143734899672957818500254654e0), (6, -8.14978701074692612513997267357e0), (7, -1.85200656599969598641566180701e1), (8, 2.27394870993505042818970056734e1), (9, 2.49360555267965238987089396762e0), (10, -3.0467644718982195003823669022e0)),
    12: ((1, 2.27331014751653820792359768449e0), (4, -1.05344954667372501984066689879e1), (5, -2.00087205822486249909675718444e0), (6, -1.79589318631187989172765950534e1), (7, 2.79488845294199600508499808837e1), (8, -2.85899827713502369474065508674e0), (9, -8.87285693353062954433549289258e0), (10, 1.23605671757943030647266201528e1), (11, 6.43392746015763530355970484046e-1)),
    14: ((1, 5.61675022830479523392909219681e-2), (7, 2.53500210216624811088794765333e-1), (8, -2.46239037470802489917441475441e-1), (9, -1.24191423263816360469010140626e-1), (10, 1.5329179827876569731206322685e-1), (11, 8.20105229563468988491666602057e-3), (12, 7.56789766054569976138603589584e-3), (13, -8.298e-3)),
    15: ((1, 3.18346481635021405060768473261e-2), (6, 2.83009096723667755288322961402e-2), (7, 5.35419883074385676223797384372e-2), (8, -5.49237485713909884646569340306e-2), (11, -1.08347328697249322858509316994e-4), (12, 3.82571090835658412954920192323e-4), (13, -3.40465008687404560802977114492e-4), (14, 1.41312443674632500278074618366e-1)),
    16: ((1, -4.28896301583791923408573538692e-1), (6, -4.69762141536116384314449447206e0), (7, 7.68342119606259904184240953878e0), (8, 4.06898981839711007970213554331e0), (9, 3.56727187455281109270669543021e-1), (13, -1.39902416515901462129418009734e-3), (14, 2.9475147891527723389556272149e0), (15, -9.15095847217987001081870187138e0)),
}
_B = ((1, 5.42937341165687622380535766363e-2), (6, 4.45031289275240888144113950566e0), (7, 1.89151789931450038304281599044e0), (8, -5.8012039600105847814672114227e0), (9, 3.1116436695781989440891606237e-1), (10, -1.52160949662516078556178806805e-1), (11, 2.01365400804030348374776537501e-1), (12, 4.47106157277725905176885569043e-2))
_ER = ((1, 0.1312004499419488073250102996e-01), (6, -0.1225156446376204440720569753e+01), (7, -0.4957589496572501915214079952e+00), (8, 0.1664377182454986536961530415e+01), (9, -0.3503288487499736816886487290e+00), (10, 0.3341791187130174790297318841e+00), (11, 0.8192320648511571246570742613e-01), (12, -0.2235530786388629525884427845e-01))
_BHH = (0.244094488188976377952755905512e+00, 0.733846688281611857341361741547e+00, 0.220588235294117647058823529412e-01)
_D4 = ((1, -0.84289382761090128651353491142e+01), (6, 0.56671495351937776962531783590e+00), (7, -0.30689499459498916912797304727e+01), (8, 0.23846676565120698287728149680e+01), (9, 0.21170345824450282767155149946e+01), (10, -0.87139158377797299206789907490e+00), (11, 0.22404374302607882758541771650e+01), (12, 0.63157877876946881815570249290e+00), (13, -0.88990336451333310820698117400e-01), (14, 0.18148505520854727256656404962e+02), (15, -0.91946323924783554000451984436e+01), (16, -0.44360363875948939664310572000e+01))
_D5 = ((1, 0.10427508642579134603413151009e+02), (6, 0.24228349177525818288430175319e+03), (7, 0.16520045171727028198505394887e+03), (8, -0.37454675472269020279518312152e+03), (9, -0.22113666853125306036270938578e+02), (10, 0.77334326684722638389603898808e+01), (11, -0.30674084731089398182061213626e+02), (12, -0.93321305264302278729567221706e+01), (13, 0.15697238121770843886131091075e+02), (14, -0.31139403219565177677282850411e+02), (15, -0.93529243588444783865713862664e+01), (16, 0.35816841486394083752465898540e+02))
_D6 = ((1, 0.19985053242002433820987653617e+02), (6, -0.38703730874935176555105901742e+03), (7, -0.18917813819516756882830838328e+03), (8, 0.52780815920542364900561016686e+03), (9, -0.11573902539959630126141871134e+02), (10, 0.68812326946963000169666922661e+01), (11, -0.10006050966910838403183860980e+01), (12, 0.77771377980534432092869265740e+00), (13, -0.27782057523535084065932004339e+01), (14, -0.60196695231264120758267380846e+02), (15, 0.84320405506677161018159903784e+02), (16, 0.11992291136182789328035130030e+02))
_D7 = ((1, -0.25693933462703749003312586129e+02), (6, -0.15418974869023643374053993627e+03), (7, -0.23152937917604549567536039109e+03), (8, 0.35763911791061412378285349910e+03), (9, 0.93405324183624310003907691704e+02), (10, -0.37458323136451633156875139351e+02), (11, 0.10409964950896230045147246184e+03), (12, 0.29840293426660503123344363579e+02), (13, -0.43533456590011143754432175058e+02), (14, 0.96324553959188282948394950600e+02), (15, -0.39177261675615439165231486172e+02), (16, -0.14972683625798562581422125276e+03))


def _lin(y, h, terms, ks):
    """y + h * sum(coef * k_j) componentwise."""
    n = len(y)
    acc = [0.0] * n
    for j, coef in terms:
        k = ks[j]
        for i in range(n):
            acc[i] += coef * k[i]
    return [y[i] + h * acc[i] for i in range(n)]


class Step:
    """One DOP853 step from (t0, y0) with slope k1; dense output on demand."""

    def __init__(self, f, t0, y0, k1, h):
        self.f, self.t0, self.y0, self.h = f, t0, y0, h
        ks = {1: k1}
        for i in range(2, 13):
            ti = t0 + (h if i == 12 else _C[i] * h)
            ks[i] = f(ti, _lin(y0, h, _A[i], ks))
        n = len(y0)
        inc = [0.0] * n
        for j, coef in _B:
            k = ks[j]
            for i in range(n):
                inc[i] += coef * k[i]
        self.y1 = [y0[i] + h * inc[i] for i in range(n)]
        self.err5 = [0.0] * n
        for j, coef in _ER:
            k = ks[j]
            for i in range(n):
                self.err5[i] += coef * k[i]
        self.err3 = [inc[i] - _BHH[0] * k1[i] - _BHH[1] * ks[9][i] - _BHH[2] * ks[12][i] for i in range(n)]
        self.ks = ks
        self.k13 = None
        self.cont = None

    def error(self, rtol, atol):
        n = len(self.y0)
        e5 = e3 = 0.0
        for i in range(n):
            sk = atol + rtol * max(abs(self.y0[i]), abs(self.y1[i]))
            e5 += (self.err5[i] / sk) ** 2
            e3 += (self.err3[i] / sk) ** 2
        deno = e5 + 0.01 * e3
        if deno <= 0.0:
            deno = 1.0
        return abs(self.h) * e5 / math.sqrt(n * deno)

    def finish(self):
        """The slope at the end (FSAL), evaluated once the step is accepted."""
        if self.k13 is None:
            self.k13 = self.f(self.t0 + self.h, self.y1)
        return self.k13

    def dense(self):
        if self.cont is None:
            f, t0, y0, h, ks = self.f, self.t0, self.y0, self.h, self.ks
            ks[13] = self.finish()
            for i in (14, 15, 16):
                ks[i] = f(t0 + _C[i] * h, _lin(y0, h, _A[i], ks))
            n = len(y0)
            r1 = list(y0)
            r2 = [self.y1[i] - y0[i] for i in range(n)]
            r3 = [h * ks[1][i] - r2[i] for i in range(n)]
            r4 = [r2[i] - h * ks[13][i] - r3[i] for i in range(n)]
            rs = []
            for table in (_D4, _D5, _D6, _D7):
                acc = [0.0] * n
                for j, coef in table:
                    k = ks[j]
                    for i in range(n):
                        acc[i] += coef * k[i]
                rs.append([h * a_ for a_ in acc])
            self.cont = (r1, r2, r3, r4, rs[0], rs[1], rs[2], rs[3])
        return self.cont

    def at(self, t):
        r1, r2, r3, r4, r5, r6, r7, r8 = self.dense()
        s = (t - self.t0) / self.h
        s1 = 1.0 - s
        return [r1[i] + s * (r2[i] + s1 * (r3[i] + s * (r4[i] + s1 * (r5[i] + s * (r6[i] + s1 * (r7[i] + s * r8[i]))))))
                for i in range(len(r1))]


# ------------------------------------------------------------------------------------------- the coin
ROLL, SLIDE, SEED = "roll", "slide", "seed"


class Stop(Exception):
    """A terminating event: name and time."""

    def __init__(self, name, t, detail=""):
        super().__init__(f"{name} at t = {t!r}{detail}")
        self.name, self.t = name, t


class Coin:
    def __init__(self, p):
        known = {"mass", "radius", "thickness", "edge_radius", "I_X", "I_Z", "g", "mu", "mu_s", "theta", "phi",
                 "psi", "omega_X", "omega_Y", "omega_Z", "x", "z", "v_x", "v_z", "duration", "sample_dt", "rtol",
                 "atol"}
        unknown = sorted(set(p) - known)
        if unknown:
            raise ValueError(f"unknown parameter(s): {', '.join(unknown)}")
        for key in ("mass", "radius", "mu", "duration"):
            if key not in p:
                raise ValueError(f"{key}: required")
        self.M = float(p["mass"])
        self.a = float(p["radius"])
        self.h = float(p.get("thickness", 0.0))
        self.rho = float(p.get("edge_radius", self.h / 2))
        if self.h == 0.0:
            self.IX = float(p.get("I_X", self.M * self.a**2 / 4))
            self.IZ = float(p.get("I_Z", self.M * self.a**2 / 2))
        else:
            if "I_X" not in p or "I_Z" not in p:
                raise ValueError("I_X, I_Z: required with a thickness")
            self.IX, self.IZ = float(p["I_X"]), float(p["I_Z"])
        self.g = float(p.get("g", 9.81))
        self.mu = float(p["mu"])
        self.mu_s = float(p.get("mu_s", self.mu))
        if not (self.M > 0 and self.a > 0 and self.h >= 0 and 0 <= self.rho <= self.h / 2 + 1e-300
                and self.rho < self.a and self.IX > 0 and self.IZ > 0 and self.g > 0 and self.mu >= 0
                and self.mu_s >= self.mu):
            raise ValueError("parameters out of range (M, a, I > 0; 0 <= rho <= h/2; 0 <= mu <= mu_s)")
        self.e = max(self.h / 2 - self.rho, 0.0)   # corner offset h/2 - rho
        self.sigma = 1.0
        self.reach = self.a - self.rho               # a - rho
        # Slip direction used when |s| is below the floor (the start of a slide from s = 0), and the
        # prescribed direction of a seed interval (mu = mu_s start).
        self.stored_dir = (1.0, 0.0, 0.0)
        self.seed = None

    # --------------------------------------------------------------------------------- kinematics
    def frame(self, y):
        """Everything the dynamics needs at state y: (q_hat, e_Z, e_X, e_Y, omega, c, c_dot, cos_theta)."""
        nq = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3])
        q = (y[0] / nq, y[1] / nq, y[2] / nq, y[3] / nq)
        eZ = quat_rotate(q, (0.0, 0.0, 1.0))
        cu = math.sqrt(eZ[0] * eZ[0] + eZ[2] * eZ[2])        # cos(theta) = |y x e_Z|
        eX = (eZ[2] / cu, 0.0, -eZ[0] / cu)
        eY = cross(eZ, eX)
        w = (y[4], y[5], y[6])
        deZ = cross(w, eZ)
        du = (deZ[2], 0.0, -deZ[0])                          # d/dt (y x e_Z)
        deX = scale(1.0 / cu, sub(du, scale(dot(eX, du), eX)))
        deY = add(cross(deZ, eX), cross(eZ, deX))
        se = self.sigma * self.e
        c = (-self.reach * eY[0] + se * eZ[0], -self.reach * eY[1] + se * eZ[1] - self.rho,
             -self.reach * eY[2] + se * eZ[2])
        c_dot = add(scale(-self.reach, deY), scale(se, deZ))
        return q, eZ, eX, eY, w, c, c_dot, cu

    def inertia(self, eZ, x):
        return add(scale(self.IX, x), scale((self.IZ - self.IX) * dot(eZ, x), eZ))

    def inertia_inv(self, eZ, x):
        return add(scale(1.0 / self.IX, x), scale((1.0 / self.IZ - 1.0 / self.IX) * dot(eZ, x), eZ))

    def delassus(self, eZ, c):
        """x -> W x = x / M + (I^-1 (c x x)) x c   (docs/sliding.md 1.9)."""
        Minv = 1.0 / self.M
        return lambda x: add(scale(Minv, x), cross(self.inertia_inv(eZ, cross(c, x)), c))

    def bias(self, eZ, w, c, c_dot):
        """b of s_P' = W R + b: -g y + (I^-1 (-omega x I omega)) x c + omega x c-dot."""
        gyro = cross(w, self.inertia(eZ, w))
        b = add(cross(self.inertia_inv(eZ, scale(-1.0, gyro)), c), cross(w, c_dot))
        return (b[0], b[1] - self.g, b[2]), gyro

    def slip(self, y, c=None, w=None):
        if c is None:
            _, _, _, _, w, c, _, _ = self.frame(y)
        s = add((y[10], y[11], y[12]), cross(w, c))
        return (s[0], 0.0, s[2]), s[1]

    def slip_rate(self, y, k):
        """Horizontal d/dt of the slip s = v_G + omega x c along the slope k: a_G + omega-dot x c + omega x c-dot."""
        _, _, _, _, w, c, c_dot, _ = self.frame(y)
        r = add(add((k[10], k[11], k[12]), cross((k[4], k[5], k[6]), c)), cross(w, c_dot))
        return (r[0], 0.0, r[2])

    def rolling_reaction(self, eZ, c, b):
        W = self.delassus(eZ, c)
        return solve3((W((1.0, 0.0, 0.0)), W((0.0, 1.0, 0.0)), W((0.0, 0.0, 1.0))), scale(-1.0, b))

    def sliding_reaction(self, eZ, c, b, s_hat, mu):
        """R = N (y - mu s_hat) with N from the held contact; also D = M y . W (y - mu s_hat)."""
        x = (-mu * s_hat[0], 1.0 - mu * s_hat[1], -mu * s_hat[2])
        Wx = self.delassus(eZ, c)(x)
        N = -b[1] / Wx[1]
        return scale(N, x), N, self.M * Wx[1]

    def slip_direction(self, t, sh, ns):
        if self.seed is not None and self.seed["active"]:
            sd = self.seed
            tau = t - sd["t"]
            d = (-sd["f"][0] + sd["d"] * tau * sd["fp"][0], 0.0, -sd["f"][2] + sd["d"] * tau * sd["fp"][2])
            return scale(1.0 / norm(d), d)
        if ns > self.s_floor:
            return scale(1.0 / ns, sh)
        return self.stored_dir

    def make_rhs(self, mode):
        mu = self.mu

        def f(t, y):
            q, eZ, eX, eY, w, c, c_dot, cu = self.frame(y)
            b, gyro = self.bias(eZ, w, c, c_dot)
            power = 0.0
            if mode == ROLL:
                R = self.rolling_reaction(eZ, c, b)
            else:
                sh, _ = self.slip(y, c, w)
                ns = norm(sh)
                s_hat = self.slip_direction(t, sh, ns)
                R, N, _ = self.sliding_reaction(eZ, c, b, s_hat, mu)
                power = mu * N * dot(s_hat, sh)                   # -F . s, = mu N |s| while sliding
            wdot = self.inertia_inv(eZ, sub(cross(c, R), gyro))
            qw = (0.0, w[0], w[1], w[2])
            qd = quat_mul(qw, q)
            Minv = 1.0 / self.M
            return [0.5 * qd[0], 0.5 * qd[1], 0.5 * qd[2], 0.5 * qd[3],
                    wdot[0], wdot[1], wdot[2],
                    y[10], y[11], y[12],
                    R[0] * Minv, R[1] * Minv - self.g, R[2] * Minv,
                    power]
        return f

    # --------------------------------------------------------------------------------- observables
    def observe(self, y, mode, t=None):
        q, eZ, eX, eY, w, c, c_dot, cu = self.frame(y)
        b, _ = self.bias(eZ, w, c, c_dot)
        sh, s_vert = self.slip(y, c, w)
        ns = norm(sh)
        if mode == ROLL:
            R = self.rolling_reaction(eZ, c, b)
            N = R[1]
            D = None
        else:
            s_hat = self.slip_direction(t if t is not None else 0.0, sh, ns)
            R, N, D = self.sliding_reaction(eZ, c, b, s_hat, self.mu)
        F = (R[0], 0.0, R[2])
        v = (y[10], y[11], y[12])
        E = 0.5 * self.M * dot(v, v) + 0.5 * dot(w, self.inertia(eZ, w)) + self.M * self.g * y[8]
        theta = math.atan2(-eZ[1], cu)
        H = -c[1]
        return {"q": q, "eZ": eZ, "eX": eX, "eY": eY, "w": w, "c": c, "b": b, "R": R, "N": N, "F": F,
                "Fn": norm(F), "slip": sh, "slip_speed": ns, "slip_vertical": s_vert, "D": D, "E": E,
                "theta": theta, "H": H, "qnorm": math.sqrt(sum(y[i] * y[i] for i in range(4)))}

    def energy(self, y):
        q, eZ, eX, eY, w, c, c_dot, cu = self.frame(y)
        v = (y[10], y[11], y[12])
        return 0.5 * self.M * dot(v, v) + 0.5 * dot(w, self.inertia(eZ, w)) + self.M * self.g * y[8]

    def initial_state(self, p):
        th, ph, ps = float(p.get("theta", 0.0)), float(p.get("phi", 0.0)), float(p.get("psi", 0.0))
        if not abs(th) < math.radians(89):
            raise ValueError("theta: |theta| must be below 89 deg")
        if self.e > 0 and th == 0.0:
            raise ValueError("theta: a cornered rim (edge_radius < thickness/2) may not start upright")
        self.sigma = -1.0 if th < 0 else 1.0
        q = quat_from_euler(th, ph, ps)
        eX = (math.cos(ph), 0.0, -math.sin(ph))
        eY = (math.sin(th) * math.sin(ph), math.cos(th), math.sin(th) * math.cos(ph))
        eZ = (math.cos(th) * math.sin(ph), -math.sin(th), math.cos(th) * math.cos(ph))
        wX, wY, wZ = (float(p.get(k, 0.0)) for k in ("omega_X", "omega_Y", "omega_Z"))
        w = add(add(scale(wX, eX), scale(wY, eY)), scale(wZ, eZ))
        y = list(q) + list(w) + [float(p.get("x", 0.0)), 0.0, float(p.get("z", 0.0))] + [0.0, 0.0, 0.0, 0.0]
        _, eZq, eXq, eYq, _, c, _, _ = self.frame(y)
        # The quaternion's axes are the rows of docs/seed.md §2 (psi turns only b1, b2 about e_Z).
        assert norm(sub(eZq, eZ)) < 1e-14 and norm(sub(eXq, eX)) < 1e-14 and norm(sub(eYq, eY)) < 1e-14
        y[8] = -c[1]                                           # height of G: the contact on the floor
        wc = cross(w, c)
        if ("v_x" in p) != ("v_z" in p):
            raise ValueError("v_x, v_z: give both or neither")
        if "v_x" in p:
            y[10], y[11], y[12] = float(p["v_x"]), -wc[1], float(p["v_z"])
        else:
            y[10], y[11], y[12] = -wc[0], -wc[1], -wc[2]
        self.v_scale = max(norm((y[10], y[11], y[12])), self.a * norm(w), math.sqrt(self.g * self.a))
        self.t_scale = 1.0 / max(norm(w), math.sqrt(self.g / self.a))
        self.s_floor = 1e-15 * self.v_scale
        # Below s_snap the slip is taken as zero (the coin lands): above the integration's own noise in the
        # velocities, ~ atol + rtol |v| per step (the slip's direction is stiff at small |s|, docs/sliding.md §4.4).
        rtol, atol = float(p.get("rtol", 1e-12)), float(p.get("atol", 1e-12))
        self.s_snap = max(1e-12 * self.v_scale, 10.0 * (atol + rtol * self.v_scale))
        return y

    # --------------------------------------------------------------------------------- switching
    def consistent_direction(self, y, ref, mu):
        """At zero slip: the attracting directions s_hat with s-dot(s_hat) = lambda s_hat, lambda > 0 (4.9); the one
        nearest ref (an angle in the floor plane)."""
        q, eZ, eX, eY, w, c, c_dot, cu = self.frame(y)
        b, _ = self.bias(eZ, w, c, c_dot)
        W = self.delassus(eZ, c)

        def sdot(beta):
            s_hat = (math.cos(beta), 0.0, math.sin(beta))
            R, N, D = self.sliding_reaction(eZ, c, b, s_hat, mu)
            a_ = add(W(R), b)
            return a_[0] * -math.sin(beta) + a_[2] * math.cos(beta), a_[0] * math.cos(beta) + a_[2] * math.sin(beta), N, D

        n = 720
        grid = [2 * math.pi * i / n for i in range(n + 1)]
        vals = [sdot(bt) for bt in grid]
        roots = []
        for i in range(n):
            p0, p1 = vals[i][0], vals[i + 1][0]
            if p0 > 0 >= p1:          # perpendicular rate decreasing through 0: attracting
                lo, hi = grid[i], grid[i + 1]
                for _ in range(80):
                    mid = 0.5 * (lo + hi)
                    if sdot(mid)[0] > 0:
                        lo = mid
                    else:
                        hi = mid
                bt = 0.5 * (lo + hi)
                perp, along, N, D = sdot(bt)
                if along > 0 and N > 0 and D > 0:
                    roots.append(bt)
        if not roots:
            return None
        ref_angle = math.atan2(ref[2], ref[0])
        best = min(roots, key=lambda bt: abs(math.remainder(bt - ref_angle, 2 * math.pi)))
        return (math.cos(best), 0.0, math.sin(best))

    def horizontal_compliance(self, eZ, c):
        """W_c (2x2 over x, z), nu (2), y.W.y: the condensed compliance and N's sensitivity (4.2)-(4.3)."""
        W = self.delassus(eZ, c)
        Wy, Wx, Wz = W((0.0, 1.0, 0.0)), W((1.0, 0.0, 0.0)), W((0.0, 0.0, 1.0))
        Wyy = Wy[1]
        Wc = ((Wx[0] - Wy[0] * Wy[0] / Wyy, Wz[0] - Wy[0] * Wy[2] / Wyy),
              (Wx[2] - Wy[2] * Wy[0] / Wyy, Wz[2] - Wy[2] * Wy[2] / Wyy))
        nu = (-Wy[0] / Wyy, -Wy[2] / Wyy)
        return Wc, nu, Wyy


# ------------------------------------------------------------------------------------------- the run
def find_root(g, ta, tb, ga=None):
    """t in (ta, tb] where g falls through 0: g(ta) > 0 >= g(tb). Bisection with the Illinois secant."""
    fa = g(ta) if ga is None else ga
    fb = g(tb)
    side = 0
    for _ in range(200):
        if tb - ta <= 4e-16 * max(1.0, abs(tb)):
            break
        tm = (ta * fb - tb * fa) / (fb - fa) if fa != fb else 0.5 * (ta + tb)
        if not (ta < tm < tb):
            tm = 0.5 * (ta + tb)
        fm = g(tm)
        if fm > 0:
            ta, fa = tm, fm
            if side == 1:
                fb *= 0.5
            side = 1
        else:
            tb, fb = tm, fm
            if side == -1:
                fa *= 0.5
            side = -1
    return tb


class Run:
    """Integrates one parameter set; rows go to emit(list_of_values)."""

    def __init__(self, params, emit=None, log=None, extra=False, on_step=None):
        self.p = dict(params)
        self.coin = Coin(self.p)
        self.emit = emit
        self.log = log or (lambda msg: None)
        self.extra = extra
        self.switches = []           # (t, "slides" | "rolls", info dict)
        self.end = "duration"
        self.stats = {"steps": 0, "rejected": 0, "guided": 0, "rhs": 0}
        self.drift = {"height": 0.0, "vertical_slip": 0.0, "qnorm": 0.0, "rolling_slip": 0.0, "energy_balance": 0.0}
        self.prev_psi = None
        self.slip_grown = True
        self.on_step = on_step       # called as on_step(t, y, mode) after every accepted step

    # ------------------------------------------------------------------------------------ output
    def row(self, t, y, mode):
        coin = self.coin
        o = coin.observe(y, mode, t)
        w = o["w"]
        vals = [t, o["theta"], dot(w, o["eX"]), dot(w, o["eY"]), dot(w, o["eZ"]), y[7], y[9], y[10], y[12], o["E"],
                0.0 if mode == ROLL else o["slip_speed"], 0 if mode == ROLL else 1]
        if self.extra:
            eZ = o["eZ"]
            phi = math.atan2(eZ[0], eZ[2])
            q = o["q"]
            u = quat_rotate((q[0], -q[1], -q[2], -q[3]), Y_HAT)
            psi = math.atan2(u[0], u[1])
            if self.prev_psi is not None:
                psi += 2 * math.pi * round((self.prev_psi - psi) / (2 * math.pi))
            self.prev_psi = psi
            vals += [phi, psi, y[8], y[11], o["N"], o["Fn"], y[13], y[8] - o["H"]]
        return vals

    def sample(self, step, t_lo, t_hi, mode, include_hi=False):
        while self.k <= self.k_max:
            tk = self.k * self.dt
            if tk < t_lo - 1e-300:
                self.k += 1
                continue
            if tk < t_hi or (include_hi and tk <= t_hi):
                y = step.y0 if tk == step.t0 else step.at(tk)
                if self.emit is not None:
                    self.emit(self.row(tk, y, mode))
                self.rows_out += 1
                self.k += 1
            else:
                break

    # ------------------------------------------------------------------------------------ events
    def events(self, mode):
        coin = self.coin
        ev = []
        if mode == ROLL:
            ev.append(("cone", lambda o: coin.mu_s * o["N"] - o["Fn"]))
        else:
            ev.append(("painleve", lambda o: o["D"]))
        ev.append(("lift-off", lambda o: o["N"]))
        if coin.e > 0:
            ev.append(("corner-switch", lambda o: coin.sigma * o["theta"]))
        ev.append(("coin-flat", lambda o: math.radians(89.5) - abs(o["theta"])))
        return ev

    # ------------------------------------------------------------------------------------ switches
    def start_slide(self, t, y, why):
        coin = self.coin
        _, _, _, _, w, c, _, _ = coin.frame(y)
        wc = cross(w, c)
        y[10], y[12] = -wc[0], -wc[2]                      # zero slip exactly (it is within the tolerance)
        o = coin.observe(y, ROLL)
        Fr, Nr = o["F"], o["N"]
        if o["Fn"] == 0.0:
            raise Stop("slip-undefined", t, ": zero rolling friction at the switch")
        f_hat = scale(1.0 / o["Fn"], Fr)
        info = {"N_roll": Nr, "F_roll": Fr, "contract_dir": scale(-1.0, f_hat), "why": why}
        if o["Fn"] - coin.mu * Nr > 1e-9 * coin.mu * Nr:
            # The rolling demand lies strictly outside the kinetic cone (mu < mu_s at the cone's edge, or a start
            # outside it): the slip grows linearly (4.5).
            # First order in mu_s - mu: s_hat = -f_hat + delta f_perp (docs/sliding.md 4.10).
            Wc, nu, _ = coin.horizontal_compliance(o["eZ"], o["c"])
            f2, fp = (f_hat[0], f_hat[2]), (-f_hat[2], f_hat[0])
            w_fp = fp[0] * (Wc[0][0] * f2[0] + Wc[0][1] * f2[1]) + fp[1] * (Wc[1][0] * f2[0] + Wc[1][1] * f2[1])
            w_pp = fp[0] * (Wc[0][0] * fp[0] + Wc[0][1] * fp[1]) + fp[1] * (Wc[1][0] * fp[0] + Wc[1][1] * fp[1])
            nu_f, nu_p = nu[0] * f2[0] + nu[1] * f2[1], nu[0] * fp[0] + nu[1] * fp[1]
            mk = coin.mu
            info["delta_first_order"] = (mk - coin.mu_s) * w_fp / (mk * (w_pp * (1 - mk * nu_f) + mk * nu_p * w_fp))
            info["f_perp"] = (fp[0], 0.0, fp[1])
            d = coin.consistent_direction(y, scale(-1.0, f_hat), coin.mu)
            if d is None:
                d = scale(-1.0, f_hat)
                self.log(f"no self-consistent slip direction at t = {t!r}; using -F_roll")
            coin.stored_dir = d
            info["start"] = "linear"
            info["dir"] = d
            mode = SLIDE
        else:
            mode = self.seed_slide(t, y, o, f_hat, info)
        self.slip_grown = False
        self.switches.append((t, "slides", info))
        self.log(f"slides at t = {t!r}")
        return mode

    def seed_slide(self, t, y, o, f_hat, info):
        """mu = mu_s: the slip starts as -lambda t^2 / 2 f_hat, the friction direction turning at d (4.7)-(4.8)."""
        coin = self.coin
        mu = coin.mu
        delta = 1e-4 * coin.t_scale
        f_roll = coin.make_rhs(ROLL)
        k1 = f_roll(t, y)
        outs = []
        for hh in (delta, -delta):
            yy = Step(f_roll, t, y, k1, hh).y1
            outs.append(coin.observe(yy, ROLL))
        Fdot = ((outs[0]["F"][0] - outs[1]["F"][0]) / (2 * delta), (outs[0]["F"][2] - outs[1]["F"][2]) / (2 * delta))
        Ndot = (outs[0]["N"] - outs[1]["N"]) / (2 * delta)
        Wc, nu, Wyy = coin.horizontal_compliance(o["eZ"], o["c"])
        f2 = (f_hat[0], f_hat[2])
        fp = (-f2[1], f2[0])
        det = Wc[0][0] * Wc[1][1] - Wc[0][1] * Wc[1][0]
        Wi = ((Wc[1][1] / det, -Wc[0][1] / det), (-Wc[1][0] / det, Wc[0][0] / det))
        Wi_f = (Wi[0][0] * f2[0] + Wi[0][1] * f2[1], Wi[1][0] * f2[0] + Wi[1][1] * f2[1])
        E = (mu * Ndot * f2[0] - Fdot[0], mu * Ndot * f2[1] - Fdot[1])
        kappa = -(f2[0] * E[0] + f2[1] * E[1])
        beta = (f2[0] - mu * nu[0]) * Wi_f[0] + (f2[1] - mu * nu[1]) * Wi_f[1]
        if not (kappa > 0 and beta > 0):
            raise Stop("slip-start", t, f": no quadratic slip start (kappa = {kappa!r}, beta = {beta!r})")
        lam = kappa / beta
        d = ((fp[0] * E[0] + fp[1] * E[1]) + lam * (fp[0] * Wi_f[0] + fp[1] * Wi_f[1])) / (mu * o["N"])
        t0 = 1e-3 * min(coin.t_scale, mu * o["N"] / kappa)
        coin.seed = {"t": t, "f": f_hat, "fp": (fp[0], 0.0, fp[1]), "d": d, "active": True, "end": t + t0,
                     "lambda": lam}
        info.update({"start": "quadratic", "kappa": kappa, "beta": beta, "lambda": lam, "d": d, "t0": t0,
                     "W_c": Wc, "nu": nu, "dir": scale(-1.0, f_hat)})
        self.log(f"quadratic slip start: kappa = {kappa!r} N/s, lambda = {lam!r} m/s^3, d = {d!r} rad/s, "
                 f"seed interval t0 = {t0!r} s")
        return SEED

    def land(self, t, y):
        """|s| ~ 0 while sliding: zero it; roll if the rolling reaction fits the cone, else slide on."""
        coin = self.coin
        sh, _ = coin.slip(y)
        # What is left of the slip (<= 1e-12 of the speed scale) decays in tau = |s| / rate: apply that
        # interval's increments (an Euler step; time itself is not moved, an error of tau ~ 1e-14 s), then zero
        # the rounding residue.
        ns = norm(sh)
        if ns > 0:
            k = coin.make_rhs(SLIDE)(t, y)
            rate = dot(coin.slip_rate(y, k), sh) / ns
            if rate < 0:
                tau = ns / -rate
                for i in range(14):
                    y[i] += tau * k[i]
            sh, _ = coin.slip(y)
        y[10] -= sh[0]
        y[12] -= sh[2]
        o = coin.observe(y, ROLL)
        info = {"N_roll": o["N"], "F_roll": o["F"], "residual_slip": norm(sh)}
        if o["N"] > 0 and o["Fn"] <= coin.mu_s * o["N"]:
            self.switches.append((t, "rolls", info))
            self.log(f"rolls at t = {t!r}")
            return ROLL
        ref = scale(-1.0 / o["Fn"], o["F"]) if o["Fn"] > 0 else coin.stored_dir
        d = coin.consistent_direction(y, ref, coin.mu)
        if d is None:
            raise Stop("slip-undefined", t, ": the slip stops, rolling does not fit the cone and no slip direction")
        coin.stored_dir = d
        info["dir"] = d
        self.slip_grown = False
        self.switches.append((t, "slides on", info))
        self.log(f"slip reaches 0 at t = {t!r} outside the cone: slides on")
        return SLIDE

    # ------------------------------------------------------------------------------------ integration
    def run(self):
        coin, p = self.coin, self.p
        self.dt = float(p.get("sample_dt", 0.01))
        duration = float(p["duration"])
        rtol, atol = float(p.get("rtol", 1e-12)), float(p.get("atol", 1e-12))
        if not (self.dt > 0 and duration >= 0):
            raise ValueError("duration >= 0 and sample_dt > 0 required")
        y = coin.initial_state(p)
        self.E0 = coin.energy(y)
        self.k_max = int(math.floor(duration / self.dt * (1 + 1e-12) + 1e-12))
        t_end = max(duration, self.k_max * self.dt)
        self.k = 0
        self.rows_out = 0
        t = 0.0
        sh, _ = coin.slip(y)
        if norm(sh) > coin.s_floor:
            mode = SLIDE
            coin.stored_dir = scale(1.0 / norm(sh), sh)
        else:
            mode = ROLL
            o = coin.observe(y, ROLL)
            if o["N"] <= 0:
                raise Stop("lift-off", 0.0, ": the rolling start needs N <= 0")
            if coin.mu_s * o["N"] - o["Fn"] < 0:
                mode = self.start_slide(t, y, "initial rolling reaction outside the cone")
        h = 1e-3 * coin.t_scale
        try:
            while t < t_end:
                f = coin.make_rhs(mode)
                k1 = f(t, y)
                seg_end = t_end
                if mode == SEED:
                    seg_end = min(t_end, coin.seed["end"])
                land_now = False
                if mode == SLIDE:
                    s0, _ = coin.slip(y)
                    n0 = norm(s0)
                    if n0 > coin.s_floor:
                        rate = dot(coin.slip_rate(y, k1), s0) / n0
                        if rate < 0 and t + n0 / -rate < seg_end:
                            seg_end = t + n0 / -rate          # aim at the predicted zero of the slip
                while True:
                    hh = min(h, seg_end - t)
                    last = hh >= seg_end - t
                    if hh <= 1e-14 * coin.t_scale:
                        if mode == SLIDE:
                            land_now = True
                            break
                        raise Stop("step-size", t, ": the step size underflowed")
                    st = Step(f, t, y, k1, hh)
                    err = st.error(rtol, atol)
                    if not math.isfinite(err) or err > 1.0:
                        self.stats["rejected"] += 1
                        h = hh * (0.2 if not math.isfinite(err) else max(0.2, 0.9 * err ** (-1 / 8)))
                        continue
                    if mode == SLIDE:
                        s0, _ = coin.slip(y)
                        n0 = norm(s0)
                        d0 = scale(1.0 / n0, s0) if n0 > coin.s_floor else coin.stored_dir
                        s1, _ = coin.slip(st.y1)
                        if dot(s1, d0) <= 0:
                            # The slip speed reaches 0 inside the step: retry onto that root (the stages past it
                            # would see the friction reversed).
                            self.stats["guided"] += 1
                            if n0 <= coin.s_snap:
                                land_now = True
                                break
                            rate = dot(coin.slip_rate(y, k1), d0)
                            tr = t + n0 / -rate if rate < 0 else t + 0.5 * hh
                            if not (t < tr < t + hh):
                                tr = t + 0.5 * hh
                            h = tr - t
                            seg_end = min(seg_end, tr)
                            continue
                    break
                if land_now:
                    mode = self.land(t, y)
                    continue
                self.stats["steps"] += 1
                # Smooth events: earliest fall through 0 inside the step.
                o1 = coin.observe(st.y1, mode, t + hh)
                hit = None
                for name, gfun in self.events(mode):
                    if gfun(o1) <= 0:
                        o0 = coin.observe(y, mode, t)
                        g0 = gfun(o0)
                        if g0 <= 0:
                            self.sample(st, t, t, mode, include_hi=True)
                            raise Stop(name, t)
                        te = find_root(lambda tt: gfun(coin.observe(st.at(tt), mode, tt)), t, t + hh, g0)
                        if hit is None or te < hit[0]:
                            hit = (te, name)
                if hit is not None:
                    te, name = hit
                    self.sample(st, t, te, mode)
                    y = st.at(te)
                    t = te
                    if name != "cone":
                        raise Stop(name, te)
                    mode = self.start_slide(t, y, "rolling reaction leaves the cone")
                    h = 1e-6 * coin.t_scale
                    continue
                self.sample(st, t, t + hh, mode, include_hi=(last and seg_end >= t_end))
                t = seg_end if last else t + hh
                y = st.y1
                self.check(y, mode, t)
                if mode == SEED and t >= coin.seed["end"]:
                    sh, _ = coin.slip(y)
                    coin.stored_dir = scale(1.0 / norm(sh), sh)
                    coin.seed["active"] = False
                    coin.seed["slip_at_end"] = norm(sh)
                    coin.seed["dir_at_end"] = coin.stored_dir
                    mode = SLIDE
                if mode == SLIDE:
                    sh, _ = coin.slip(y)
                    ns = norm(sh)
                    if ns > 2 * coin.s_snap:
                        self.slip_grown = True
                    # Land once the slip has grown out of the noise and decays into it again (a slide that has just
                    # started from s = 0 grows through this band).
                    elif ns <= coin.s_snap and self.slip_grown and (
                            ns == 0.0 or dot(coin.slip_rate(y, st.finish()), sh) < 0):
                        mode = self.land(t, y)
                h = hh * (6.0 if err == 0 else min(6.0, max(0.2, 0.9 * err ** (-1 / 8))))
        except Stop as stop:
            self.end = stop.name
            self.log(f"run ends: {stop}")
            if stop.name in ("step-size", "slip-undefined", "slip-start"):
                raise
        self.t_final, self.y_final, self.mode_final = t, y, mode
        return self

    def check(self, y, mode, t):
        if self.on_step is not None:
            self.on_step(t, y, mode)
        coin = self.coin
        o = coin.observe(y, mode, t)
        d = self.drift
        d["height"] = max(d["height"], abs(y[8] - o["H"]))
        d["vertical_slip"] = max(d["vertical_slip"], abs(o["slip_vertical"]))
        d["qnorm"] = max(d["qnorm"], abs(o["qnorm"] - 1.0))
        if mode == ROLL:
            d["rolling_slip"] = max(d["rolling_slip"], o["slip_speed"])
        d["energy_balance"] = max(d["energy_balance"], abs(o["E"] + y[13] - self.E0))

    def report(self):
        d = self.drift
        self.log(f"end: {self.end} at t = {self.t_final!r}; {self.stats['steps']} steps, {self.stats['rejected']} rejected, "
                 f"{self.stats['guided']} guided onto zero slip; drift: |y_G - H| {d['height']:.2e} m, vertical slip "
                 f"{d['vertical_slip']:.2e} m/s, ||q| - 1| {d['qnorm']:.2e}, slip while rolling {d['rolling_slip']:.2e} m/s, "
                 f"|E + dissipated - E0| {d['energy_balance']:.2e} J (E0 = {self.E0!r} J)")


HEADER = "t,theta,omega_X,omega_Y,omega_Z,x,z,v_x,v_z,energy,slip_speed,sliding"
EXTRA = ",phi,psi,y,v_y,normal_force,friction_force,dissipated,drift_height"


def fmt(v):
    return str(v) if isinstance(v, int) else repr(float(v) + 0.0)   # + 0.0: no "-0.0"


# ------------------------------------------------------------------------------------------- self-test
def _run(params):
    rows = []
    run = Run(params, emit=rows.append).run()
    return run, rows


def _lcg(seed):
    """Deterministic pseudo-random numbers in [0, 1) (no dependence on Python's random module)."""
    state = [seed]

    def nxt():
        state[0] = (6364136223846793005 * state[0] + 1442695040888963407) % (1 << 64)
        return (state[0] >> 11) / float(1 << 53)
    return nxt


def self_test():
    failures = []

    def check(name, ok, detail):
        print(f"{'ok    ' if ok else 'FAILED'} {name}: {detail}")
        if not ok:
            failures.append(name)

    # 1. The analytic skid (docs/sliding.md §5): thin disk, and a fully rounded thick coin with its own I_Z.
    for label, extra_p in (("thin disk", {}),
                           ("rounded rim, I_Z = 0.55 M a^2", {"thickness": 0.003, "edge_radius": 0.0015,
                                                               "I_X": 0.008 * (0.0125**2 / 4 + 0.003**2 / 12),
                                                               "I_Z": 0.55 * 0.008 * 0.0125**2})):
        M, a, mu, g, v0 = 0.008, 0.0125, 0.3, 9.81, 0.5
        p = {"mass": M, "radius": a, "mu": mu, "g": g, "v_x": v0, "v_z": 0.0, "duration": 0.1, "sample_dt": 0.01}
        p.update(extra_p)
        run, rows = _run(p)
        IZ = run.coin.IZ
        t_star = v0 / (mu * g * (1 + M * a * a / IZ))
        v_after = v0 * M * a * a / (IZ + M * a * a)
        work = M * v0 * v0 / 2 - 0.5 * (M + IZ / a**2) * v_after**2
        kinds = [k for _, k, _ in run.switches]
        t_sw = run.switches[0][0] if run.switches else float("nan")
        yf = run.y_final
        e_t = abs(t_sw - t_star) / t_star
        e_v = abs(yf[10] - v_after) / v_after
        e_w = abs(yf[13] - work) / work
        e_e = abs(run.E0 - run.coin.energy(yf) - work) / work
        check(f"skid, {label}", kinds == ["rolls"] and max(e_t, e_v, e_w, e_e) < 1e-9 and run.mode_final == ROLL,
              f"t* {t_sw!r} (exact {t_star!r}, rel. err {e_t:.1e}); speed after {yf[10]!r} ({v_after!r}, {e_v:.1e}); "
              f"friction work {yf[13]!r} J ({work!r}, {e_w:.1e}); E0 - E {e_e:.1e}")

    # 2. A rolling start inside the cone stays rolling and keeps its energy.
    wobble = {"mass": 0.00567, "radius": 0.01213, "theta": 0.3, "omega_X": 3.0, "omega_Y": 2.0, "omega_Z": -30.0,
              "duration": 0.5, "sample_dt": 0.01}
    run, rows = _run(dict(wobble, mu=0.5))
    ratio = max(abs(run.coin.energy(run.y_final) - run.E0), run.drift["energy_balance"]) / run.E0
    check("rolling inside the cone (mu = 0.5, F/N up to 0.39)", not run.switches and ratio < 1e-10
          and run.drift["rolling_slip"] < 1e-10,
          f"switches {len(run.switches)}; max |E - E0| / E0 = {ratio:.1e}; max slip {run.drift['rolling_slip']:.1e} m/s; "
          f"|y_G - H| {run.drift['height']:.1e} m")

    # 3. A tilted spinning coin that skids then rolls; energy + friction work conserved; self-convergence.
    skid = {"mass": 0.00567, "radius": 0.01213, "mu": 0.3, "theta": 0.3, "omega_Y": 2.0, "omega_Z": -30.0,
            "v_x": 0.2, "v_z": 0.05, "duration": 0.5, "sample_dt": 0.01}
    run, rows = _run(skid)
    fine, rows_f = _run(dict(skid, rtol=1e-13, atol=1e-13))
    kinds = [k for _, k, _ in run.switches]
    bal = run.drift["energy_balance"] / run.E0
    d_t = abs(run.switches[0][0] - fine.switches[0][0]) if run.switches and fine.switches else float("nan")
    d_rows = max(abs(u - v) for r, rf in zip(rows, rows_f) for u, v in zip(r[1:10], rf[1:10]))
    check("tilted spinning coin skids then rolls", kinds == ["rolls"] and bal < 1e-10 and d_t < 1e-10
          and d_rows < 1e-9 and len(rows) == len(rows_f) == 51,
          f"rolls at t = {run.switches[0][0]!r}; |E + W - E0| / E0 = {bal:.1e}; rtol 1e-12 vs 1e-13: switch "
          f"{d_t:.1e} s, rows (rad, rad/s, m, m/s) {d_rows:.1e}")

    # 3b. The same from a steady circle (theta = 0.3 rad, omega_Z = -30 rad/s, omega_Y its root of rim.md 5.1) whose
    #     centre is launched off its rolling velocity (0.3639, 0): a short skid, then a gentle wobble.
    circle = dict(skid, omega_Y=-5.263469899354806, v_x=0.3, v_z=0.05, duration=1.0)
    run, rows = _run(circle)
    fine, rows_f = _run(dict(circle, rtol=1e-13, atol=1e-13))
    kinds = [k for _, k, _ in run.switches]
    bal = run.drift["energy_balance"] / run.E0
    d_t = abs(run.switches[0][0] - fine.switches[0][0]) if run.switches and fine.switches else float("nan")
    d_rows = max(abs(u - v) for r, rf in zip(rows, rows_f) for u, v in zip(r[1:10], rf[1:10]))
    check("perturbed steady circle skids then rolls", kinds == ["rolls"] and bal < 1e-10 and d_t < 1e-10
          and d_rows < 1e-9 and len(rows) == len(rows_f) == 101,
          f"rolls at t = {run.switches[0][0]!r}; |E + W - E0| / E0 = {bal:.1e}; rtol 1e-12 vs 1e-13: switch "
          f"{d_t:.1e} s, rows {d_rows:.1e}")

    # 4. Rolling -> sliding, mu < mu_s (linear start) and mu = mu_s (quadratic start).
    for label, mus in (("mu = 0.28 < mu_s = 0.3", 0.3), ("mu = mu_s = 0.3", None)):
        p = dict(wobble, mu=(0.28 if mus else 0.3), duration=0.3)
        if mus:
            p["mu_s"] = mus
        trace = []
        rows = []
        run = Run(p, emit=rows.append, on_step=lambda t, y, mode: trace.append((t, list(y), mode))).run()
        fine, rows_f = _run(dict(p, rtol=1e-13, atol=1e-13))
        bal = run.drift["energy_balance"] / run.E0
        first = run.switches[0]
        info = first[2]
        d_sw = max(abs(a_[0] - b_[0]) for a_, b_ in zip(run.switches, fine.switches))
        d_rows = max(abs(u - v) for r, rf in zip(rows, rows_f) for u, v in zip(r[1:10], rf[1:10]))
        same = [k for _, k, _ in run.switches] == [k for _, k, _ in fine.switches]
        detail = (f"{len(run.switches)} switches, first: slides at {first[0]!r}; |E + W - E0| / E0 = {bal:.1e}; "
                  f"rtol 1e-12 vs 1e-13: switches {d_sw:.1e} s, rows {d_rows:.1e}")
        ok = first[1] == "slides" and bal < 1e-10 and same and d_sw < 1e-9 and d_rows < 1e-7
        if info["start"] == "linear":
            cd, dd = info["contract_dir"], info["dir"]
            delta = dot(dd, info["f_perp"]) / dot(dd, cd)          # s_hat = -f_hat + delta f_perp
            pred = info["delta_first_order"]
            ok = ok and abs(delta - pred) <= 0.2 * abs(pred) + 1e-12
            detail += (f"; the slip emerges at {delta:.3e} rad from -F_roll (4.9), first order in mu_s - mu (4.10): "
                       f"{pred:.3e} rad")
        else:
            sd = run.coin.seed
            pred = 0.5 * sd["lambda"] * (sd["end"] - sd["t"]) ** 2
            rel = abs(sd["slip_at_end"] - pred) / pred
            dd, cd = sd["dir_at_end"], info["contract_dir"]
            ang = math.degrees(math.atan2(cd[0] * dd[2] - cd[2] * dd[0], dot(cd, dd)))
            # (4.7)-(4.8) after the seed, tau = 10 t0 from the switch: |s| = lambda tau^2 / 2 and the direction
            # -f_hat + d tau f_perp, each to O(tau / T).
            t_s, t0 = sd["t"], sd["end"] - sd["t"]
            tt, yy, _ = min((x for x in trace if x[2] == SLIDE), key=lambda x: abs(x[0] - t_s - 10 * t0))
            tau = tt - t_s
            s_, _ = run.coin.slip(yy)
            grow = norm(s_) / (0.5 * sd["lambda"] * tau * tau)
            turn = (dot(s_, sd["fp"]) / dot(s_, cd)) / (sd["d"] * tau)
            ok = ok and rel < 1e-3 and abs(grow - 1) < 0.01 and abs(turn - 1) < 0.01
            detail += (f"; seed t0 = {t0:.2e} s: |s| = {sd['slip_at_end']:.4e} vs lambda t0^2 / 2 = {pred:.4e} "
                       f"(rel. {rel:.1e}); at tau = {tau:.2e} s: |s| / (lambda tau^2 / 2) = {grow:.5f}, "
                       f"slip direction's turn / (d tau) = {turn:.5f}")
        check(f"rolling -> sliding, {label}", ok, detail)

    # 5. The right-hand side against the docs' other forms at pseudo-random states: sliding (1.5), (1.7) by
    #    Sherman-Morrison and N in the seed frame; rolling against docs/rim.md (2.8)-(2.9).
    nxt = _lcg(20261201)
    worst_s = worst_r = 0.0
    for trial in range(200):
        thick = trial % 2 == 1
        p = {"mass": 0.005 + 0.01 * nxt(), "radius": 0.01 + 0.02 * nxt(), "mu": 1.5 * nxt(), "duration": 1.0,
             "theta": (nxt() - 0.5) * 2.6, "phi": 6.0 * nxt(), "psi": 6.0 * nxt(),
             "omega_X": 40 * (nxt() - 0.5), "omega_Y": 40 * (nxt() - 0.5), "omega_Z": 80 * (nxt() - 0.5),
             "v_x": nxt() - 0.5, "v_z": nxt() - 0.5}
        if thick:
            h_ = 0.3 * p["radius"] * nxt()
            p.update({"thickness": h_, "edge_radius": h_ / 2 * nxt(), "I_X": p["mass"] * p["radius"]**2 * (0.2 + 0.2 * nxt()),
                      "I_Z": p["mass"] * p["radius"]**2 * (0.4 + 0.3 * nxt())})
        coin = Coin(p)
        y = coin.initial_state(p)
        k = coin.make_rhs(SLIDE)(0.0, y)
        o = coin.observe(y, SLIDE)
        q, eZ, eX, eY, w, c, c_dot, cu = coin.frame(y)
        wdot = (k[4], k[5], k[6])
        s_hat = scale(1.0 / o["slip_speed"], o["slip"])
        # (1.5)-(1.7): m = c x y, k = c x (y - mu s_hat), N0 = M g - M (omega x c-dot) . y.
        m_ = cross(c, Y_HAT)
        kv = cross(c, sub(Y_HAT, scale(coin.mu, s_hat)))
        N0 = coin.M * coin.g - coin.M * dot(cross(w, c_dot), Y_HAT)
        rhs = add(scale(-1.0, cross(w, coin.inertia(eZ, w))), scale(N0, kv))
        Iinv_rhs = coin.inertia_inv(eZ, rhs)
        Iinv_k = coin.inertia_inv(eZ, kv)
        D = 1 + coin.M * dot(m_, Iinv_k)
        wdot_sm = sub(Iinv_rhs, scale(coin.M * dot(m_, Iinv_rhs) / D, Iinv_k))   # Sherman-Morrison
        N_sm = N0 - coin.M * dot(m_, wdot_sm)
        scale_w = max(norm(wdot), 1e-300)
        worst_s = max(worst_s, norm(sub(wdot, wdot_sm)) / scale_w, abs(o["N"] - N_sm) / abs(o["N"]),
                      abs(o["D"] - D) / abs(D))
        # N in the seed frame: M (g - (H - rho) omega_X^2 - Lambda omega_X'), omega_X' = d/dt (omega . e_X).
        th = o["theta"]
        A = coin.a - coin.rho + coin.rho * math.cos(th)
        B = coin.sigma * coin.e + coin.rho * math.sin(th)
        H = A * math.cos(th) + B * math.sin(th)
        Lam = A * math.sin(th) - B * math.cos(th)
        wX, wY, wZ = dot(w, eX), dot(w, eY), dot(w, eZ)
        Om = (wX, wY, -wY * math.tan(th))                       # the frame XYZ's rate, XYZ components
        wv = (wX, wY, wZ)
        wdot_xyz = (dot(wdot, eX), dot(wdot, eY), dot(wdot, eZ))
        wprime = sub(wdot_xyz, cross(Om, wv))                   # component derivative in XYZ
        N_seed = coin.M * (coin.g - (H - coin.rho) * wX**2 - Lam * wprime[0])
        worst_s = max(worst_s, abs(N_seed - o["N"]) / abs(o["N"]))
        # Rolling: docs/rim.md (2.8)-(2.9).
        kr = coin.make_rhs(ROLL)(0.0, y)
        wdot_r = (kr[4], kr[5], kr[6])
        wp_r = sub((dot(wdot_r, eX), dot(wdot_r, eY), dot(wdot_r, eZ)), cross(Om, wv))
        M_, rho_, tn = coin.M, coin.rho, math.tan(th)
        L = A + B * tn
        V = A * wZ + B * wY
        Gx = wY * (coin.a - rho_ + B * tn) + rho_ * math.sin(th) * wZ
        fX = -coin.IZ * wY * wZ - coin.IX * tn * wY**2 - M_ * L * V * wY + M_ * rho_ * Lam * wX**2 + M_ * coin.g * Lam
        fY = wX * (coin.IX * tn * wY + coin.IZ * wZ + M_ * B * Gx)
        fZ = wX * M_ * A * Gx
        mXX = coin.IX + M_ * (A * A + B * B)
        mYY, mYZ, mZZ = coin.IX + M_ * B * B, M_ * A * B, coin.IZ + M_ * A * A
        det = mYY * mZZ - mYZ * mYZ
        wp_rim = (fX / mXX, (mZZ * fY - mYZ * fZ) / det, (mYY * fZ - mYZ * fY) / det)
        worst_r = max(worst_r, norm(sub(wp_r, wp_rim)) / max(norm(wp_rim), 1.0))
    check("sliding right-hand side = (1.5)-(1.7) by Sherman-Morrison and N of the seed frame", worst_s < 1e-9,
          f"200 random states (thin and thick), worst relative difference {worst_s:.1e}")
    check("rolling right-hand side = docs/rim.md (2.8)-(2.9)", worst_r < 1e-9,
          f"200 random states, worst relative difference {worst_r:.1e}")

    # 6. Determinism: the same parameters give the same bytes.
    import io
    outs = []
    for _ in range(2):
        buf = io.StringIO()
        simulate_to(dict(skid, duration=0.2), buf, quiet=True)
        outs.append(buf.getvalue())
    check("deterministic output", outs[0] == outs[1], f"{len(outs[0])} bytes twice")

    print("all reference self-tests passed" if not failures else f"{len(failures)} FAILED: {', '.join(failures)}")
    return 0 if not failures else 1


# ------------------------------------------------------------------------------------------- command line
def simulate_to(params, out, extra=False, quiet=False):
    log = (lambda msg: None) if quiet else (lambda msg: print(f"sliding_reference: {msg}", file=sys.stderr))
    out.write(HEADER + (EXTRA if extra else "") + "\n")
    run = Run(params, emit=lambda vals: out.write(",".join(fmt(v) for v in vals) + "\n"), log=log, extra=extra)
    run.run()
    run.report()
    return run


def main(argv):
    args = [a_ for a_ in argv[1:] if not a_.startswith("--")]
    flags = {a_ for a_ in argv[1:] if a_.startswith("--")}
    if "--help" in flags or "-h" in argv[1:]:
        print(__doc__)
        return 0
    if "--self-test" in flags:
        return self_test()
    if len(args) != 1 or flags - {"--extra"}:
        print("usage: sliding_reference.py 'JSON' | @file.json [--extra]  |  --self-test", file=sys.stderr)
        return 2
    text = args[0]
    if text.startswith("@"):
        with open(text[1:]) as fh:
            text = fh.read()
    try:
        params = json.loads(text)
        if not isinstance(params, dict):
            raise ValueError("the parameters must be a JSON object")
        probe = Run(params)  # validate before writing anything
        probe.coin.initial_state(params)
        if not (float(params.get("sample_dt", 0.01)) > 0 and float(params["duration"]) >= 0):
            raise ValueError("duration >= 0 and sample_dt > 0 required")
    except (ValueError, TypeError, json.JSONDecodeError) as exc:
        print(f"sliding_reference: {exc}", file=sys.stderr)
        return 2
    try:
        simulate_to(params, sys.stdout, extra="--extra" in flags)
    except Stop as stop:
        print(f"sliding_reference: failed: {stop}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
