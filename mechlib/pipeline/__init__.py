"""The build wing: turns executed notebooks and the book sources into the HTML and PDF book."""
