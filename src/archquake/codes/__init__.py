"""Building codes: the site's elastic spectra and the code checks of local mechanisms."""
