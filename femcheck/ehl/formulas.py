"""Classical film-thickness formulas of isothermal EHL point contacts (spec ehl-life.md §A.8).

Hamrock & Dowson (1977, ASME J. Lubr. Technol. 99:264-276, fully flooded), mean speed U = eta0 u_m/(E' Rx),
G = alpha E', W = w/(E' Rx^2), k = a/b (transverse over rolling semi-axis):
    h_c/Rx   = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k))
    h_min/Rx = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k))
Fitted to their own (coarse) numerical solutions; a sanity band, not an accuracy target.

Nijenbanning, Venner & Moes (1994, Wear 176:217-229), central film in Moes units H = (h_c/Rx) U_M^-1/2 with
D = Rx/Ry (the asymptotes rigid-isoviscous RI, elastic-isoviscous EI, rigid-piezoviscous RP, elastic-piezoviscous
EP and the blending of the paper; the blend exponent 2s/3 as in the spec, not the 2/(3s) of some public copies):
    H_RI = 145 (1 + 0.796 D^(14/15))^(-15/7) D^-1 M^-2
    H_EI = 3.18 (1 + 0.006 ln D + 0.63 D^(4/7))^(-14/25) D^(-1/15) M^(-2/15)
    H_RP = 1.29 (1 + 0.691 D)^(-2/3) L^(2/3)
    H_EP = 1.48 (1 + 0.006 ln D + 0.63 D^(4/7))^(-7/20) D^(-1/24) M^(-1/12) L^(3/4)
    H_00 = 1.8 D^-1,  s = 1.5 (1 + exp(-1.2 H_EI/H_RI))
    H_c  = {[H_RI^(3/2) + (H_EI^-4 + H_00^-4)^(-3/8)]^(2s/3) + (H_RP^-8 + H_EP^-8)^(-s/8)}^(1/s)
A fit to multigrid solutions with Barus viscosity and an incompressible lubricant.
"""
from __future__ import annotations

import numpy as np


def hamrock_dowson(U: float, G: float, W: float, k: float) -> tuple[float, float]:
    """(h_c/Rx, h_min/Rx) of Hamrock & Dowson (1977); U on the mean speed, k = a/b."""
    hc = 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1.0 - 0.61 * np.exp(-0.73 * k))
    hm = 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1.0 - np.exp(-0.68 * k))
    return float(hc), float(hm)


def moes_central(M: float, L: float, D: float = 1.0) -> float:
    """Central film H_c = (h_c/Rx) U_M^-1/2 of Nijenbanning, Venner & Moes (1994); D = Rx/Ry."""
    lnD = np.log(D)
    h_ri = 145.0 * (1.0 + 0.796 * D ** (14.0 / 15.0)) ** (-15.0 / 7.0) / D * M**-2.0
    h_ei = 3.18 * (1.0 + 0.006 * lnD + 0.63 * D ** (4.0 / 7.0)) ** (-14.0 / 25.0) * D ** (-1.0 / 15.0) \
        * M ** (-2.0 / 15.0)
    h_rp = 1.29 * (1.0 + 0.691 * D) ** (-2.0 / 3.0) * L ** (2.0 / 3.0)
    h_ep = 1.48 * (1.0 + 0.006 * lnD + 0.63 * D ** (4.0 / 7.0)) ** (-7.0 / 20.0) * D ** (-1.0 / 24.0) \
        * M ** (-1.0 / 12.0) * L**0.75
    h_00 = 1.8 / D
    s = 1.5 * (1.0 + np.exp(-1.2 * h_ei / h_ri))
    iso = (h_ri**1.5 + (h_ei**-4 + h_00**-4) ** -0.375) ** (2.0 * s / 3.0)
    piezo = (h_rp**-8 + h_ep**-8) ** (-s / 8.0)
    return float((iso + piezo) ** (1.0 / s))
