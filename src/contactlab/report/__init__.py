"""Tables, figures and the HTML report, built from results files only."""
