#!/usr/bin/python3
"""A numpy port of pycpd's AffineRegistration (pycpd 2.x, Myronenko & Song's CPD, affine), used by
`ipd bench registration --pycpd` as the Python baseline the registration speed is compared against. pycpd itself
is not installable here (no PyPI access, no Debian package); this follows its EMRegistration / AffineRegistration
code step for step: sigma2 initialisation, E-step with the outlier weight w (default 0), M-step, tolerance 0.001
on the objective, at most 100 iterations.

usage: pycpd_reference.py CASES.json OUT.json
  CASES.json: [{"a": [[x, y], ...], "b": [[x, y], ...]}, ...]  (isotropic coordinates, A is moved onto B)
  OUT.json:   [{"B": [[..], [..]], "t": [.., ..], "ms": time of register() in milliseconds}, ...]
"""
import json
import sys
import time

import numpy as np


class AffineRegistration:
    def __init__(self, X, Y, max_iterations=100, tolerance=0.001, w=0.0):
        self.X, self.Y, self.TY = X, Y, Y
        self.N, self.D = X.shape
        self.M = Y.shape[0]
        diff = X[None, :, :] - Y[:, None, :]
        self.sigma2 = np.sum(diff ** 2) / (self.D * self.M * self.N)  # initialize_sigma2
        self.tolerance, self.w, self.max_iterations = tolerance, w, max_iterations
        self.iteration, self.diff, self.q = 0, np.inf, np.inf
        self.B, self.t = np.eye(self.D), np.zeros((1, self.D))

    def register(self):
        self.transform_point_cloud()
        while self.iteration < self.max_iterations and self.diff > self.tolerance:
            self.expectation()
            self.update_transform()
            self.transform_point_cloud()
            self.update_variance()
            self.iteration += 1
        return self.B, self.t

    def expectation(self):
        P = np.sum((self.X[None, :, :] - self.TY[:, None, :]) ** 2, axis=2)
        c = (2 * np.pi * self.sigma2) ** (self.D / 2) * self.w / (1 - self.w) * self.M / self.N
        P = np.exp(-P / (2 * self.sigma2))
        den = np.sum(P, axis=0, keepdims=True)
        den = np.clip(den, np.finfo(self.X.dtype).eps, None) + c
        self.P = np.divide(P, den)
        self.Pt1 = np.sum(self.P, axis=0)
        self.P1 = np.sum(self.P, axis=1)
        self.Np = np.sum(self.P1)
        self.PX = np.matmul(self.P, self.X)

    def update_transform(self):
        muX = np.divide(np.sum(self.PX, axis=0), self.Np)
        muY = np.divide(np.sum(np.dot(np.transpose(self.P), self.Y), axis=0), self.Np)
        self.X_hat = self.X - np.tile(muX, (self.N, 1))
        Y_hat = self.Y - np.tile(muY, (self.M, 1))
        self.A = np.dot(np.dot(np.transpose(self.X_hat), np.transpose(self.P)), Y_hat)
        self.YPY = np.dot(np.dot(np.transpose(Y_hat), np.diag(self.P1)), Y_hat)
        self.B = np.linalg.solve(np.transpose(self.YPY), np.transpose(self.A))
        self.t = np.transpose(muX) - np.dot(np.transpose(self.B), np.transpose(muY))

    def transform_point_cloud(self):
        self.TY = np.dot(self.Y, self.B) + np.tile(self.t, (self.M, 1))

    def update_variance(self):
        qprev = self.q
        trAB = np.trace(np.dot(self.A, self.B))
        xPx = np.dot(np.transpose(self.Pt1), np.sum(np.multiply(self.X_hat, self.X_hat), axis=1))
        trBYPYP = np.trace(np.dot(np.dot(self.B, self.YPY), self.B))
        self.q = (xPx - 2 * trAB + trBYPYP) / (2 * self.sigma2) + self.D * self.Np / 2 * np.log(self.sigma2)
        self.diff = np.abs(self.q - qprev)
        self.sigma2 = (xPx - trAB) / (self.Np * self.D)
        if self.sigma2 <= 0:
            self.sigma2 = self.tolerance / 10


def main():
    cases = json.load(open(sys.argv[1]))
    out = []
    for c in cases:
        a, b = np.array(c["a"], float), np.array(c["b"], float)
        if len(a) < 2 or len(b) < 2:
            out.append({"B": [[1, 0], [0, 1]], "t": [0, 0], "ms": 0.0})
            continue
        start = time.perf_counter()
        reg = AffineRegistration(X=b, Y=a)  # pycpd moves Y onto X
        B, t = reg.register()
        ms = (time.perf_counter() - start) * 1000
        # pycpd applies row vectors: y' = y B + t, i.e. the linear map is B transposed.
        out.append({"B": np.transpose(B).tolist(), "t": np.ravel(t).tolist(), "ms": ms})
    json.dump(out, open(sys.argv[2], "w"))


if __name__ == "__main__":
    main()
