"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""

KNOWN = {
    'contact.Conical.force:z_s': ((
        'contact.Conical.force(z_s=huge) -> returned non-finite (inf)'
    ), False),
    'contact.ForceCurve:*': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.ForceCurve:force': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.ForceCurve:name': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.ForceCurve:spring_constant': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.ForceCurve:z_np': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.Parabolic.depth_for_radius:contact_radius': ((
        'contact.Parabolic.depth_for_radius(contact_radius=huge) -> returned non-finite (inf)'
    ), False),
    'contact.Parabolic.force:z_s': ((
        'contact.Parabolic.force(z_s=huge) -> returned non-finite (inf)'
    ), False),
    'contact.Parabolic.profile:r': ((
        'contact.Parabolic.profile(r=huge) -> returned non-finite (inf)'
    ), False),
    'contact.Pyramidal.force:z_s': ((
        'contact.Pyramidal.force(z_s=huge) -> returned non-finite (inf)'
    ), False),
    'contact.StandardLinearSolid:*': ((
        'contact.StandardLinearSolid(relaxed_modulus=1e+244) -> ValueError not naming relaxed_'
        "modulus: 'instantaneous_modulus must be in [1e+244, inf) Pa, got 2e+06'...'"
    ), False),
    'contact.StandardLinearSolid:relaxed_modulus': ((
        'contact.StandardLinearSolid(relaxed_modulus=huge) -> ValueError not naming relaxed_mo'
        "dulus: 'instantaneous_modulus must be in [1e+300, inf) Pa, got 2e+06'...'\n"
        'contact.StandardLinearSolid(relaxed_modulus=bigint) -> ValueError not naming relaxed_'
        "modulus: 'instantaneous_modulus must be in [1e+09, inf) Pa, got 2e+06'...'"
    ), False),
    'contact.approach_retract:work_of_adhesion': ((
        'contact.approach_retract(work_of_adhesion=nan) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=None) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=str) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=bool) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=complex) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=object) -> accepted silently\n'
        'contact.approach_retract(work_of_adhesion=nan-array) -> accepted silently'
    ), False),
    'contact.fit_curve:*': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.fit_curve:force': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.fit_curve:poisson_ratio': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.fit_curve:position': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.fit_curve:pyramid_form': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.fit_curve:spring_constant': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.fit_curve:tip': ((
        'tests/test_api_campaign.py:115: TypeError'
    ), False),
    'contact.hereditary_force:time': ((
        "contact.hereditary_force(time=list) -> ValueError not naming time: 'indentation must "
        "have 2 elements (same as its companion array), got 50'"
    ), False),
    'contact.jkr_curve:*': ((
        'contact.jkr_curve(reduced_modulus=1e-320) -> returned non-finite (0: array with 10 no'
        'n-finite of 10)'
    ), False),
    'contact.jkr_curve:contact_radius': ((
        'contact.jkr_curve(contact_radius=huge) -> returned non-finite (0: np.float64(inf))'
    ), False),
    'contact.jkr_curve:work_of_adhesion': ((
        'contact.jkr_curve(work_of_adhesion=huge) -> returned non-finite (1: array with 10 non'
        '-finite of 10)'
    ), False),
    'contact.jkr_instability:radius': ((
        'contact.jkr_instability(radius=huge) -> returned non-finite (1: inf)'
    ), False),
    'contact.make_tip:key': ((
        'contact.make_tip(key=list) -> TypeError not naming key: "unhashable type: \'list\'"\n'
        'contact.make_tip(key=2d) -> TypeError not naming key: "unhashable type: \'numpy.nd'
        'array\'"\n'
        'contact.make_tip(key=empty) -> TypeError not naming key: "unhashable type: \'numpy'
        '.ndarray\'"\n'
        'contact.make_tip(key=nan-array) -> TypeError not naming key: "unhashable type: \'n'
        'umpy.ndarray\'"'
    ), False),
    'contact.surface_displacement:z_s': ((
        'contact.surface_displacement(z_s=list) -> TypeError not naming z_s: "float() argument'
        ' must be a string or a real number, not \'list\'"\n'
        "contact.surface_displacement(z_s=2d) -> TypeError not naming z_s: 'only 0-dimensional"
        " arrays can be converted to Python scalars'\n"
        "contact.surface_displacement(z_s=empty) -> TypeError not naming z_s: 'only 0-dimensio"
        "nal arrays can be converted to Python scalars'"
    ), False),
    'contact.synthetic_curve:*': ((
        'contact.synthetic_curve(z_np_range=0.0) -> TypeError not naming z_np_range: "\'flo'
        'at\' object is not subscriptable"'
    ), False),
    'contact.synthetic_curve:contact_point': ((
        "contact.synthetic_curve(contact_point=huge) -> ValueError not naming contact_point: '"
        "z_np must be in [-100, 100] m, got -1e+300 (at index 0)'\n"
        'contact.synthetic_curve(contact_point=-huge) -> ValueError not naming contact_point: '
        "'z_np must be in [-100, 100] m, got 1e+300 (at index 0)'\n"
        'contact.synthetic_curve(contact_point=bigint) -> ValueError not naming contact_point:'
        " 'z_np must be in [-100, 100] m, got -1e+09 (at index 0)'"
    ), False),
    'contact.synthetic_curve:seed': ((
        "contact.synthetic_curve(seed=nan) -> TypeError not naming seed: 'SeedSequence expects"
        " int or sequence of ints for entropy not nan'\n"
        "contact.synthetic_curve(seed=inf) -> TypeError not naming seed: 'SeedSequence expects"
        " int or sequence of ints for entropy not inf'\n"
        "contact.synthetic_curve(seed=-inf) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not -inf'\n"
        "contact.synthetic_curve(seed=str) -> TypeError not naming seed: 'SeedSequence expects"
        " int or sequence of ints for entropy not 1e-6'\n"
        'contact.synthetic_curve(seed=bool) -> accepted silently\n'
        "contact.synthetic_curve(seed=complex) -> TypeError not naming seed: 'SeedSequence exp"
        "ects int or sequence of ints for entropy not (1+1j)'\n"
        "contact.synthetic_curve(seed=object) -> TypeError not naming seed: 'SeedSequence expe"
        "cts int or sequence of ints for entropy not Foreign()'\n"
        "contact.synthetic_curve(seed=zero) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not 0.0'\n"
        "contact.synthetic_curve(seed=negative) -> TypeError not naming seed: 'SeedSequence ex"
        "pects int or sequence of ints for entropy not -1.0'\n"
        "contact.synthetic_curve(seed=huge) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not 1e+300'\n"
        "contact.synthetic_curve(seed=-huge) -> TypeError not naming seed: 'SeedSequence expec"
        "ts int or sequence of ints for entropy not -1e+300'\n"
        "contact.synthetic_curve(seed=tiny) -> TypeError not naming seed: 'SeedSequence expect"
        "s int or sequence of ints for entropy not 1e-300'"
    ), False),
    'contact.synthetic_curve:z_np_range': ((
        'contact.synthetic_curve(z_np_range=nan) -> TypeError not naming z_np_range: "\'flo'
        'at\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=inf) -> TypeError not naming z_np_range: "\'flo'
        'at\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=-inf) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=None) -> TypeError not naming z_np_range: "\'No'
        'neType\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=bool) -> TypeError not naming z_np_range: "\'bo'
        'ol\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=complex) -> TypeError not naming z_np_range: "'
        '\'complex\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=object) -> TypeError not naming z_np_range: "\''
        'Foreign\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=zero) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=negative) -> TypeError not naming z_np_range: '
        '"\'float\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=huge) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=-huge) -> TypeError not naming z_np_range: "\'f'
        'loat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=tiny) -> TypeError not naming z_np_range: "\'fl'
        'oat\' object is not subscriptable"\n'
        'contact.synthetic_curve(z_np_range=bigint) -> TypeError not naming z_np_range: "\''
        'int\' object is not subscriptable"\n'
        "contact.synthetic_curve(z_np_range=empty) -> IndexError: 'index 0 is out of bounds fo"
        "r axis 0 with size 0'"
    ), False),
    'contact.viscoelastic_approach_retract:*': ((
        'contact.viscoelastic_approach_retract(speed=1e-320) -> returned non-finite (time: arr'
        'ay with 118 non-finite of 119)'
    ), False),
    'contact.z_np_limit:work_of_adhesion': ((
        'contact.z_np_limit(work_of_adhesion=nan) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=None) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=str) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=bool) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=complex) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=object) -> accepted silently\n'
        'contact.z_np_limit(work_of_adhesion=nan-array) -> accepted silently'
    ), False),
    'samples.Sample:name': ((
        'samples.Sample(name=nan) -> accepted silently\n'
        'samples.Sample(name=bool) -> accepted silently\n'
        'samples.Sample(name=complex) -> accepted silently\n'
        'samples.Sample(name=object) -> accepted silently\n'
        'samples.Sample(name=nan-array) -> accepted silently'
    ), False),
    'samples.grating:*': ((
        "samples.grating(pixel_size=286) -> ValueError not naming pixel_size: 'period must be "
        "in [572, inf] m, got 5e-07'"
    ), False),
    'samples.grating:pixel_size': ((
        "samples.grating(pixel_size=huge) -> ValueError not naming pixel_size: 'period must be"
        " in [2e+300, inf] m, got 5e-07'\n"
        "samples.grating(pixel_size=bigint) -> ValueError not naming pixel_size: 'period must "
        "be in [2e+09, inf] m, got 5e-07'"
    ), False),
    'samples.particles:radius': ((
        "samples.particles(radius=huge) -> OverflowError: 'cannot convert float infinity to in"
        "teger'"
    ), False),
    'samples.rough_surface:*': ((
        "samples.rough_surface(pixel_size=1e-33) -> ValueError not naming pixel_size: 'correla"
        "tion_length must be in (0, 6.4e-32] m, got 2e-08'"
    ), False),
    'samples.rough_surface:pixel_size': ((
        "samples.rough_surface(pixel_size=tiny) -> ValueError not naming pixel_size: 'correlat"
        "ion_length must be in (0, 6.4e-299] m, got 2e-08'"
    ), False),
    'transducers.AstigmaticDetection.focus_error:d': ((
        'transducers.AstigmaticDetection.focus_error(d=huge) -> returned non-finite (np.float6'
        '4(nan))\n'
        'transducers.AstigmaticDetection.focus_error(d=-huge) -> returned non-finite (np.float'
        '64(nan))'
    ), False),
    'transducers.AstigmaticDetection.spot_radii:d': ((
        'transducers.AstigmaticDetection.spot_radii(d=huge) -> returned non-finite (0: np.floa'
        't64(inf))\n'
        'transducers.AstigmaticDetection.spot_radii(d=-huge) -> returned non-finite (0: np.flo'
        'at64(inf))'
    ), False),
    'transducers.Photothermal.frequency_response:f': ((
        'transducers.Photothermal.frequency_response(f=huge) -> returned non-finite (response:'
        ' np.complex128(nan+nanj))'
    ), False),
    'transducers.Photothermal.thermal_lag:f': ((
        'transducers.Photothermal.thermal_lag(f=huge) -> returned non-finite (array with 1 non'
        '-finite of 1, 1 NaN)'
    ), False),
    'transducers.PiezoAcoustic.base_transfer:f': ((
        'transducers.PiezoAcoustic.base_transfer(f=huge) -> returned non-finite (np.complex128'
        '(nan+nanj))'
    ), False),
    'transducers.PiezoAcoustic.frequency_response:f': ((
        'transducers.PiezoAcoustic.frequency_response(f=huge) -> returned non-finite (response'
        ': np.complex128(nan+nanj))'
    ), False),
    'transducers.SignalChain.stage:name': ((
        "transducers.SignalChain.stage(name=2d) -> ValueError not naming name: 'The truth valu"
        "e of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "transducers.SignalChain.stage(name=empty) -> ValueError not naming name: 'The truth v"
        "alue of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "transducers.SignalChain.stage(name=nan-array) -> ValueError not naming name: 'The tru"
        'th value of an array with more than one element is ambiguous. Use a.any() or a.all(..'
        ".'"
    ), False),
    'transducers.quantity:label': ((
        'transducers.quantity(label=str) -> accepted silently'
    ), False),
}
