"""Messages of failed mission legs name what a mission can do (issue 26): `mission plan` has
no --resolution, so a leg whose routing window reached its size limit is not told "a coarser
resolution reaches further" but to split the leg. Input: a real window-limited route (a
0.8 m/s head current, 1 m/s vehicle, a 4000-node window limit), put through the mission's
leg builder.
"""

from __future__ import annotations

from glideplan.fields.field import UniformField
from glideplan.missions.field_mission import LEG_WINDOW_ADVICE, _field_leg
from glideplan.routing import RouteSettings, route
from glideplan.routing.route import WINDOW_ADVICE


def test_window_limit_leg_advises_a_waypoint_not_a_resolution():
    r = route(UniformField(-0.8, 0.0), (0.0, 0.0), (0.0, 0.5), 1.0,
              settings=RouteSettings(cells=40, max_nodes=4000))
    assert r.unreachable_reason == "window_limit"
    assert WINDOW_ADVICE in r.message  # the route itself (Python, CLI route) keeps it
    leg = _field_leg(0, r)
    assert not leg.ok
    assert "resolution" not in leg.status_text
    assert LEG_WINDOW_ADVICE in leg.status_text
