"""Nonlinear-programming refinement (CasADi + IPOPT)."""
from .smoothing import SmoothResult, WarmStart, resample, smooth_path, smoothing_objective

__all__ = ["SmoothResult", "WarmStart", "resample", "smooth_path", "smoothing_objective"]
