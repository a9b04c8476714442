"""Nonlinear-programming refinement (CasADi Opti + IPOPT)."""
from .smoothing import SmoothResult, resample, smooth_path

__all__ = ["SmoothResult", "resample", "smooth_path"]
