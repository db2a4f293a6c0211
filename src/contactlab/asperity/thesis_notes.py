"""Misprints and inconsistencies found in thesis chapter 3, with the evidence.

Each note is checked by a test (``tests/asperity/``) or computed in the results; the
report lists them under the section they concern.
"""

from __future__ import annotations

NOTES: dict[str, list[str]] = {
    "single": [
        "Sec. 3.2.1 lists shear limits 4000, 5000, 6000 N/mm^2 as 0.86, 0.71, 0.57 p0: the "
        "order is reversed (with p0 = 6995.82 N/mm^2: 4000 -> 0.572, 5000 -> 0.715, "
        "6000 -> 0.858 p0).",
        "Sec. 3.2.2 gives the yield limits 5000-2000 N/mm^2 as 0.93, 0.74, 0.56, 0.37 sigma_v; "
        "with the computed von Mises maximum 0.620 p0 (z/a = 0.481) and p0 = 8568.1 N/mm^2 "
        "they are 0.941, 0.753, 0.565, 0.376 sigma_v (the printed values need sigma_v of "
        "about 0.628 p0).",
        "Below eq. 3.1 r_c is called the contact area; it is the contact radius (notation "
        "list).",
        "Eqs 3.8 and 3.9 are the same equation, printed twice with the same paragraph.",
        "The FE model's f = 1 was 'chosen to be high so it would not act as a significant "
        "limitation', but with Q_n = pi a^2 tau_max the Coulomb cap f P is 0.78, 0.94, "
        "1.17 Q_n for tau_max = 0.86, 0.71, 0.57 p0: the BEM with q <= min(f p, tau_max) "
        "slips fully at 0.75, 0.83, 0.89 Q_n.",
        "With the pure shear-limit law q <= tau_max the curve in the Fig. 3.6 normalisation "
        "is the same for every tau_max and ends at Delta_x/Delta_n = 4/pi at Q = Q_n, so "
        "differences between the three FE curves can come only from the friction cap (and "
        "the mesh).",
    ],
    "multi": [
        "The caption of Fig. 3.10 says the normalised tangential load is given by eq. 3.23; "
        "it is eq. 3.16 (eq. 3.23 is S(n)).",
        "Table 3.1 calls g(i) = i^2 and (m + 1 - i)^2 'exponentially' increasing and "
        "decreasing; they are quadratic (the labels are kept).",
        "The counts n_i = C g(i) are not integers (linearly decreasing law: 0.058 asperities "
        "at P_m); P_t/P_m only scales C and cancels from Q_t/(f P_t) and S(n).",
    ],
    "grid": [
        "After eq. 3.25 the text has u_z(0) = (1 - nu^2)/E 3P/(4D) (P/P_d)^(1/3); the exponent "
        "must be -1/3 (eq. 3.26 is right). The flattened text may have lost the sign.",
        "In the u_r formula above eq. 3.29 (1 - v) stands for (1 - nu).",
        "Fig. 3.12 text: u_cen/u_r 'approaches 1 for N > 9' for both loads. At Pt/Pd = "
        "0.00125 it is 1.21 at N = 9, 1.16 at N = 11 and 1.06 at N = 21; at Pt/Pd = 0.025 "
        "the Hertz spots overlap for N >= 5 (area ratio 0.79 at N = 5, 2.0 at N = 21), "
        "outside the model's stated validity (area ratio <= pi/4).",
    ],
}
