"""Batched filters: arrays carry any leading batch axes (trials, channels), time is explicit."""

from .interface import FilterOutput, SequentialFilter
from .kalman import KalmanFilter, KalmanOutput, kf_predict, kf_update
from .polynomial import (
    growing_memory_filter,
    growing_memory_gains,
    polynomial_observation_row,
    predict_ahead,
    taylor_transition,
)

__all__ = [
    "FilterOutput",
    "KalmanFilter",
    "SequentialFilter",
    "KalmanOutput",
    "kf_predict",
    "kf_update",
    "growing_memory_filter",
    "growing_memory_gains",
    "polynomial_observation_row",
    "predict_ahead",
    "taylor_transition",
]
