"""Vehicle models: frozen, validated dataclasses, one module per model."""

from glideplan.vehicles.base import Vehicle
from glideplan.vehicles.dubins_car import DubinsCar
from glideplan.vehicles.dubins_car_in_wind import DubinsCarInWind
from glideplan.vehicles.load_factor_glider import LoadFactorGlider
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider, dg1001m
from glideplan.vehicles.variable_speed_car import VariableSpeedCar

__all__ = [
    "DubinsCar",
    "DubinsCarInWind",
    "LoadFactorGlider",
    "QuadraticPolarGlider",
    "VariableSpeedCar",
    "Vehicle",
    "dg1001m",
]
