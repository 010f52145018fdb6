"""Vehicle models: frozen, validated dataclasses, one module per model."""

from glideplan.vehicles.base import Vehicle
from glideplan.vehicles.dubins_car import DubinsCar

__all__ = ["DubinsCar", "Vehicle"]
