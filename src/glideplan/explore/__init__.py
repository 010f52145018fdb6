"""`glideplan explore`: a local web page to plan interactively.

`catalog` builds the planners and their inputs from the registry, `state` holds the page's
state and its URL query, `solve` plans it with `glideplan.plan()` and makes the figure data,
`downloads` writes JSON/CSV/PNG, `app` is the Panel/Bokeh page and `server` serves it.
Only `catalog`, `state`, `solve` and `downloads` are importable without Panel.
"""
