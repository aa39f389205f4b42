"""Reports: HTML (jinja2) with matplotlib figures, and summary JSON. The report never runs models."""
