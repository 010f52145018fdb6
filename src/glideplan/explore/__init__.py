"""`glideplan explore`: a local web page to plan interactively.

`catalog` builds the planners and their inputs (labels with units) from the registry, `state`
holds the page's state and its URL query, `solve` plans it with `glideplan.plan()` and makes
the figure data, `downloads` writes JSON/CSV/PNG, `figures` holds the Bokeh figures (equal
scales kept in the browser), `texts` the HTML, `app` is the Panel/Bokeh page of the plane
planners (its draggable poses and view range in `plane_poses`), `page` the session's page
(plane or map mode, history entries) and `server` serves it. The map modes: `route_page`
(routes through currents or winds, `glideplan.routing.route`; its model in `route_view`,
its layers in `route_layers`), `mission_page` (waypoints of a route file,
`glideplan.missions.plan_mission`) and `reach_page` (glide reach over terrain,
`glideplan.reach.glide_reach`). Only `catalog`, `state`, `solve`, `route_view` and
`downloads` are importable without Panel.
"""
