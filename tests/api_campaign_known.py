"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""

KNOWN = {
    'plots.images.save_png:colorbar': ((
        'plots.images.save_png(colorbar=nan) -> accepted silently\n'
        'plots.images.save_png(colorbar=None) -> accepted silently\n'
        'plots.images.save_png(colorbar=str) -> accepted silently\n'
        'plots.images.save_png(colorbar=complex) -> accepted silently\n'
        'plots.images.save_png(colorbar=object) -> accepted silently\n'
        "plots.images.save_png(colorbar=2d) -> ValueError not naming colorbar: 'The truth valu"
        "e of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "plots.images.save_png(colorbar=empty) -> ValueError not naming colorbar: 'The truth v"
        "alue of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "plots.images.save_png(colorbar=nan-array) -> ValueError not naming colorbar: 'The tru"
        'th value of an array with more than one element is ambiguous. Use a.any() or a.all(..'
        ".'"
    ), False),
    'plots.images.save_png:sample': ((
        "plots.images.save_png(sample=sample-anisotropic) -> ValueError not naming sample: 'Im"
        'age size of 16x160000000 pixels is too large. It must be less than 2^23 in each direc'
        "tio...'"
    ), False),
    'plots.images.save_png:scale_bar': ((
        'plots.images.save_png(scale_bar=nan) -> accepted silently\n'
        'plots.images.save_png(scale_bar=None) -> accepted silently\n'
        'plots.images.save_png(scale_bar=str) -> accepted silently\n'
        'plots.images.save_png(scale_bar=complex) -> accepted silently\n'
        'plots.images.save_png(scale_bar=object) -> accepted silently\n'
        "plots.images.save_png(scale_bar=2d) -> ValueError not naming scale_bar: 'The truth va"
        "lue of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "plots.images.save_png(scale_bar=empty) -> ValueError not naming scale_bar: 'The truth"
        " value of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'"
        '\n'
        "plots.images.save_png(scale_bar=nan-array) -> ValueError not naming scale_bar: 'The t"
        'ruth value of an array with more than one element is ambiguous. Use a.any() or a.all('
        "...'"
    ), False),
}
