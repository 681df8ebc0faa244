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
    'controller.ContactLoop.closed_forms:input': ((
        "controller.ContactLoop.closed_forms(input=2d) -> ValueError not naming input: 'The tr"
        'uth value of an array with more than one element is ambiguous. Use a.any() or a.all(.'
        "..'\n"
        "controller.ContactLoop.closed_forms(input=empty) -> ValueError not naming input: 'The"
        ' truth value of an empty array is ambiguous. Use `array.size > 0` to check that an ar'
        "ra...'\n"
        'controller.ContactLoop.closed_forms(input=nan-array) -> ValueError not naming input: '
        "'The truth value of an array with more than one element is ambiguous. Use a.any() or "
        "a.all(...'"
    ), False),
    'controller.ContactLoop.from_cantilever:*': ((
        'controller.ContactLoop.from_cantilever(sample_damping=-2147483649) -> ValueError not '
        "naming sample_damping: 'b_s must be in [0, 1] kg/s, got -2.14748e+09'...'"
    ), False),
    'controller.ContactLoop.from_cantilever:sample_damping': ((
        'controller.ContactLoop.from_cantilever(sample_damping=nan) -> ValueError not naming s'
        "ample_damping: 'b_s must be in [0, 1] kg/s, got nan'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=inf) -> ValueError not naming s'
        "ample_damping: 'b_s must be in [0, 1] kg/s, got inf'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=-inf) -> ValueError not naming '
        "sample_damping: 'b_s must be in [0, 1] kg/s, got -inf'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=None) -> ValueError not naming '
        "sample_damping: 'b_s must be a real number, got None'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=str) -> ValueError not naming s'
        'ample_damping: "b_s must be a real number, got \'1e-6\'"\n'
        'controller.ContactLoop.from_cantilever(sample_damping=bool) -> ValueError not naming '
        "sample_damping: 'b_s must be a real number, got True'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=complex) -> ValueError not nami'
        "ng sample_damping: 'b_s must be a real number, got (1+1j)'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=list) -> ValueError not naming '
        "sample_damping: 'b_s must be a real number, got [1.0, 2.0]'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=object) -> ValueError not namin'
        "g sample_damping: 'b_s must be a real number, got Foreign()'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=negative) -> ValueError not nam'
        "ing sample_damping: 'b_s must be in [0, 1] kg/s, got -1'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=huge) -> ValueError not naming '
        "sample_damping: 'b_s must be in [0, 1] kg/s, got 1e+300'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=-huge) -> ValueError not naming'
        " sample_damping: 'b_s must be in [0, 1] kg/s, got -1e+300'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=bigint) -> ValueError not namin'
        "g sample_damping: 'b_s must be in [0, 1] kg/s, got 1e+09'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=2d) -> ValueError not naming sa'
        "mple_damping: 'b_s must be a real number, got array([[1., 1., 1.],\\n       [1., 1"
        "., 1.],\\n       [1., 1.,...'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=empty) -> ValueError not naming'
        " sample_damping: 'b_s must be a real number, got array([], dtype=float64)'...'\n"
        'controller.ContactLoop.from_cantilever(sample_damping=nan-array) -> ValueError not na'
        "ming sample_damping: 'b_s must be a real number, got array([ 0., nan])'...'"
    ), False),
    'controller.ContactLoop.from_cantilever:sample_mass': ((
        'controller.ContactLoop.from_cantilever(sample_mass=nan) -> ValueError not naming samp'
        "le_mass: 'm_s must be in [1e-18, 0.001] kg, got nan'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=inf) -> ValueError not naming samp'
        "le_mass: 'm_s must be in [1e-18, 0.001] kg, got inf'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=-inf) -> ValueError not naming sam'
        "ple_mass: 'm_s must be in [1e-18, 0.001] kg, got -inf'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=None) -> ValueError not naming sam'
        "ple_mass: 'm_s must be a real number, got None'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=str) -> ValueError not naming samp'
        'le_mass: "m_s must be a real number, got \'1e-6\'"\n'
        'controller.ContactLoop.from_cantilever(sample_mass=bool) -> ValueError not naming sam'
        "ple_mass: 'm_s must be a real number, got True'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=complex) -> ValueError not naming '
        "sample_mass: 'm_s must be a real number, got (1+1j)'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=list) -> ValueError not naming sam'
        "ple_mass: 'm_s must be a real number, got [1.0, 2.0]'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=object) -> ValueError not naming s'
        "ample_mass: 'm_s must be a real number, got Foreign()'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=zero) -> ValueError not naming sam'
        "ple_mass: 'm_s must be in [1e-18, 0.001] kg, got 0'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=negative) -> ValueError not naming'
        " sample_mass: 'm_s must be in [1e-18, 0.001] kg, got -1'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=huge) -> ValueError not naming sam'
        "ple_mass: 'm_s must be in [1e-18, 0.001] kg, got 1e+300'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=-huge) -> ValueError not naming sa'
        "mple_mass: 'm_s must be in [1e-18, 0.001] kg, got -1e+300'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=tiny) -> ValueError not naming sam'
        "ple_mass: 'm_s must be in [1e-18, 0.001] kg, got 1e-300'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=bigint) -> ValueError not naming s'
        "ample_mass: 'm_s must be in [1e-18, 0.001] kg, got 1e+09'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=2d) -> ValueError not naming sampl'
        "e_mass: 'm_s must be a real number, got array([[1., 1., 1.],\\n       [1., 1., 1.]"
        ",\\n       [1., 1.,...'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=empty) -> ValueError not naming sa'
        "mple_mass: 'm_s must be a real number, got array([], dtype=float64)'...'\n"
        'controller.ContactLoop.from_cantilever(sample_mass=nan-array) -> ValueError not namin'
        "g sample_mass: 'm_s must be a real number, got array([ 0., nan])'"
    ), False),
    'controller.ContactLoop.from_cantilever:sample_stiffness': ((
        'controller.ContactLoop.from_cantilever(sample_stiffness=nan) -> ValueError not naming'
        " sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got nan'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=inf) -> ValueError not naming'
        " sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got inf'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=-inf) -> ValueError not namin'
        "g sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got -inf'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=None) -> ValueError not namin'
        "g sample_stiffness: 'k_s must be a real number, got None'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=str) -> ValueError not naming'
        ' sample_stiffness: "k_s must be a real number, got \'1e-6\'"\n'
        'controller.ContactLoop.from_cantilever(sample_stiffness=bool) -> ValueError not namin'
        "g sample_stiffness: 'k_s must be a real number, got True'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=complex) -> ValueError not na'
        "ming sample_stiffness: 'k_s must be a real number, got (1+1j)'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=list) -> ValueError not namin'
        "g sample_stiffness: 'k_s must be a real number, got [1.0, 2.0]'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=object) -> ValueError not nam'
        "ing sample_stiffness: 'k_s must be a real number, got Foreign()'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=zero) -> ValueError not namin'
        "g sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got 0'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=negative) -> ValueError not n'
        "aming sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got -1'...'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=huge) -> ValueError not namin'
        "g sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got 1e+300'...'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=-huge) -> ValueError not nami'
        "ng sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got -1e+300'...'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=tiny) -> ValueError not namin'
        "g sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got 1e-300'...'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=bigint) -> ValueError not nam'
        "ing sample_stiffness: 'k_s must be in [1e-06, 1e+06] N/m, got 1e+09'...'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=2d) -> ValueError not naming '
        "sample_stiffness: 'k_s must be a real number, got array([[1., 1., 1.],\\n       [1"
        "., 1., 1.],\\n       [1., 1.,...'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=empty) -> ValueError not nami'
        "ng sample_stiffness: 'k_s must be a real number, got array([], dtype=float64)'...'\n"
        'controller.ContactLoop.from_cantilever(sample_stiffness=nan-array) -> ValueError not '
        "naming sample_stiffness: 'k_s must be a real number, got array([ 0., nan])'...'"
    ), False),
    'controller.ContactLoop.scan_line:x': ((
        "controller.ContactLoop.scan_line(x=list) -> ValueError not naming x: 'height must hav"
        "e 2 elements (same as its companion array), got 16'"
    ), False),
    'controller.Preset.scan:*': ((
        'controller.Preset.scan(sample=0.0) -> AttributeError: "\'float\' object has no attr'
        'ibute \'x\'"'
    ), False),
    'controller.Preset.scan:sample': ((
        'controller.Preset.scan(sample=nan) -> AttributeError: "\'float\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=inf) -> AttributeError: "\'float\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=-inf) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=str) -> AttributeError: "\'str\' object has no attrib'
        'ute \'x\'"\n'
        'controller.Preset.scan(sample=bool) -> AttributeError: "\'bool\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=complex) -> AttributeError: "\'complex\' object has n'
        'o attribute \'x\'"\n'
        'controller.Preset.scan(sample=list) -> AttributeError: "\'list\' object has no attr'
        'ibute \'x\'"\n'
        'controller.Preset.scan(sample=object) -> AttributeError: "\'Foreign\' object has no'
        ' attribute \'x\'"\n'
        'controller.Preset.scan(sample=zero) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=negative) -> AttributeError: "\'float\' object has no'
        ' attribute \'x\'"\n'
        'controller.Preset.scan(sample=huge) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=-huge) -> AttributeError: "\'float\' object has no at'
        'tribute \'x\'"\n'
        'controller.Preset.scan(sample=tiny) -> AttributeError: "\'float\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=bigint) -> AttributeError: "\'int\' object has no att'
        'ribute \'x\'"\n'
        'controller.Preset.scan(sample=2d) -> AttributeError: "\'numpy.ndarray\' object has '
        'no attribute \'x\'"\n'
        'controller.Preset.scan(sample=empty) -> AttributeError: "\'numpy.ndarray\' object h'
        'as no attribute \'x\'"\n'
        'controller.Preset.scan(sample=nan-array) -> AttributeError: "\'numpy.ndarray\' obje'
        'ct has no attribute \'x\'"'
    ), False),
    'controller.classify_roots:roots': ((
        "controller.classify_roots(roots=object) -> TypeError not naming roots: 'must be real "
        "number, not Foreign'\n"
        'controller.classify_roots(roots=nan-array) -> accepted silently'
    ), False),
    'controller.classify_roots:tol': ((
        'controller.classify_roots(tol=nan) -> accepted silently\n'
        'controller.classify_roots(tol=None) -> TypeError not naming tol: "unsupported operand'
        ' type(s) for *: \'NoneType\' and \'float\'"\n'
        'controller.classify_roots(tol=str) -> TypeError not naming tol: "can\'t multiply s'
        'equence by non-int of type \'numpy.float64\'"\n'
        'controller.classify_roots(tol=bool) -> accepted silently\n'
        'controller.classify_roots(tol=complex) -> accepted silently\n'
        'controller.classify_roots(tol=list) -> TypeError not naming tol: "can\'t multiply '
        'sequence by non-int of type \'numpy.float64\'"\n'
        'controller.classify_roots(tol=object) -> TypeError not naming tol: "unsupported opera'
        'nd type(s) for *: \'Foreign\' and \'float\'"\n'
        "controller.classify_roots(tol=2d) -> ValueError not naming tol: 'The truth value of a"
        "n array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "controller.classify_roots(tol=empty) -> ValueError not naming tol: 'The truth value o"
        "f an empty array is ambiguous. Use `array.size > 0` to check that an arra...'\n"
        "controller.classify_roots(tol=nan-array) -> ValueError not naming tol: 'The truth val"
        "ue of an array with more than one element is ambiguous. Use a.any() or a.all(...'"
    ), False),
    'controller.closed_form:*': ((
        'controller.closed_form(structure=0.0) -> KeyError: "\'step_o2_0.0\'"'
    ), False),
    'controller.closed_form:b': ((
        'controller.closed_form(b=str) -> TypeError not naming b: "step_o3_distinct() missing '
        '1 required positional argument: \'p3\'"\n'
        'controller.closed_form(b=list) -> KeyError: "\'step_o1_distinct\'"\n'
        'controller.closed_form(b=empty) -> KeyError: "\'step_o-1_distinct\'"\n'
        'controller.closed_form(b=nan-array) -> KeyError: "\'step_o1_distinct\'"'
    ), False),
    'controller.closed_form:input': ((
        'controller.closed_form(input=nan) -> KeyError: "\'nan_o2_distinct\'"\n'
        'controller.closed_form(input=inf) -> KeyError: "\'inf_o2_distinct\'"\n'
        'controller.closed_form(input=-inf) -> KeyError: "\'-inf_o2_distinct\'"\n'
        'controller.closed_form(input=None) -> KeyError: "\'None_o2_distinct\'"\n'
        'controller.closed_form(input=str) -> KeyError: "\'1e-6_o2_distinct\'"\n'
        'controller.closed_form(input=bool) -> KeyError: "\'True_o2_distinct\'"\n'
        'controller.closed_form(input=complex) -> KeyError: "\'(1+1j)_o2_distinct\'"\n'
        'controller.closed_form(input=list) -> KeyError: "\'[1.0, 2.0]_o2_distinct\'"\n'
        'controller.closed_form(input=object) -> KeyError: "\'Foreign()_o2_distinct\'"\n'
        'controller.closed_form(input=zero) -> KeyError: "\'0.0_o2_distinct\'"\n'
        'controller.closed_form(input=negative) -> KeyError: "\'-1.0_o2_distinct\'"\n'
        'controller.closed_form(input=huge) -> KeyError: "\'1e+300_o2_distinct\'"\n'
        'controller.closed_form(input=-huge) -> KeyError: "\'-1e+300_o2_distinct\'"\n'
        'controller.closed_form(input=tiny) -> KeyError: "\'1e-300_o2_distinct\'"\n'
        'controller.closed_form(input=bigint) -> KeyError: "\'1000000000_o2_distinct\'"\n'
        'controller.closed_form(input=2d) -> KeyError: "\'[[1. 1. 1.]\\\\n [1. 1. 1.]\\\\n '
        '[1. 1. 1.]]_o2_distinct\'"\n'
        'controller.closed_form(input=empty) -> KeyError: "\'[]_o2_distinct\'"\n'
        'controller.closed_form(input=nan-array) -> KeyError: "\'[ 0. nan]_o2_distinct\'"'
    ), False),
    'controller.closed_form:params': ((
        "controller.closed_form(params=nan) -> TypeError not naming params: 'Value after * mus"
        "t be an iterable, not float'\n"
        "controller.closed_form(params=inf) -> TypeError not naming params: 'Value after * mus"
        "t be an iterable, not float'\n"
        "controller.closed_form(params=-inf) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=str) -> TypeError not naming params: 'step_o2_distinct("
        ") takes 3 positional arguments but 5 were given'\n"
        "controller.closed_form(params=bool) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not bool'\n"
        "controller.closed_form(params=complex) -> TypeError not naming params: 'Value after *"
        " must be an iterable, not complex'\n"
        "controller.closed_form(params=object) -> TypeError not naming params: 'Value after * "
        "must be an iterable, not Foreign'\n"
        "controller.closed_form(params=zero) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=negative) -> TypeError not naming params: 'Value after "
        "* must be an iterable, not float'\n"
        "controller.closed_form(params=huge) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=-huge) -> TypeError not naming params: 'Value after * m"
        "ust be an iterable, not float'\n"
        "controller.closed_form(params=tiny) -> TypeError not naming params: 'Value after * mu"
        "st be an iterable, not float'\n"
        "controller.closed_form(params=bigint) -> TypeError not naming params: 'Value after * "
        "must be an iterable, not int'\n"
        "controller.closed_form(params=2d) -> TypeError not naming params: 'step_o2_distinct()"
        " takes 3 positional arguments but 4 were given'\n"
        'controller.closed_form(params=empty) -> TypeError not naming params: "step_o2_distinc'
        't() missing 2 required positional arguments: \'p1\' and \'p2\'"\n'
        'controller.closed_form(params=nan-array) -> accepted silently'
    ), False),
    'controller.closed_form:structure': ((
        'controller.closed_form(structure=nan) -> KeyError: "\'step_o2_nan\'"\n'
        'controller.closed_form(structure=inf) -> KeyError: "\'step_o2_inf\'"\n'
        'controller.closed_form(structure=-inf) -> KeyError: "\'step_o2_-inf\'"\n'
        'controller.closed_form(structure=str) -> KeyError: "\'step_o2_1e-6\'"\n'
        'controller.closed_form(structure=bool) -> KeyError: "\'step_o2_True\'"\n'
        'controller.closed_form(structure=complex) -> KeyError: "\'step_o2_(1+1j)\'"\n'
        'controller.closed_form(structure=list) -> KeyError: "\'step_o2_[1.0, 2.0]\'"\n'
        'controller.closed_form(structure=object) -> KeyError: "\'step_o2_Foreign()\'"\n'
        'controller.closed_form(structure=zero) -> KeyError: "\'step_o2_0.0\'"\n'
        'controller.closed_form(structure=negative) -> KeyError: "\'step_o2_-1.0\'"\n'
        'controller.closed_form(structure=huge) -> KeyError: "\'step_o2_1e+300\'"\n'
        'controller.closed_form(structure=-huge) -> KeyError: "\'step_o2_-1e+300\'"\n'
        'controller.closed_form(structure=tiny) -> KeyError: "\'step_o2_1e-300\'"\n'
        'controller.closed_form(structure=bigint) -> KeyError: "\'step_o2_1000000000\'"\n'
        "controller.closed_form(structure=2d) -> ValueError not naming structure: 'The truth v"
        "alue of an array with more than one element is ambiguous. Use a.any() or a.all(...'\n"
        "controller.closed_form(structure=empty) -> ValueError not naming structure: 'The trut"
        'h value of an empty array is ambiguous. Use `array.size > 0` to check that an arra...'
        "'\n"
        "controller.closed_form(structure=nan-array) -> ValueError not naming structure: 'The "
        'truth value of an array with more than one element is ambiguous. Use a.any() or a.all'
        "(...'"
    ), False),
    'controller.polished_roots:*': ((
        "controller.polished_roots(den=0.0) -> ValueError not naming den: 'negative dimensions"
        " are not allowed'"
    ), False),
    'controller.polished_roots:den': ((
        "controller.polished_roots(den=nan) -> ValueError not naming den: 'negative dimensions"
        " are not allowed'\n"
        "controller.polished_roots(den=inf) -> ValueError not naming den: 'negative dimensions"
        " are not allowed'\n"
        "controller.polished_roots(den=-inf) -> ValueError not naming den: 'negative dimension"
        "s are not allowed'\n"
        "controller.polished_roots(den=str) -> ValueError not naming den: 'negative dimensions"
        " are not allowed'\n"
        "controller.polished_roots(den=bool) -> ValueError not naming den: 'negative dimension"
        "s are not allowed'\n"
        'controller.polished_roots(den=complex) -> TypeError not naming den: "float() argument'
        ' must be a string or a real number, not \'complex\'"\n'
        'controller.polished_roots(den=object) -> TypeError not naming den: "float() argument '
        'must be a string or a real number, not \'Foreign\'"\n'
        "controller.polished_roots(den=zero) -> ValueError not naming den: 'negative dimension"
        "s are not allowed'\n"
        "controller.polished_roots(den=negative) -> ValueError not naming den: 'negative dimen"
        "sions are not allowed'\n"
        "controller.polished_roots(den=huge) -> ValueError not naming den: 'negative dimension"
        "s are not allowed'\n"
        "controller.polished_roots(den=-huge) -> ValueError not naming den: 'negative dimensio"
        "ns are not allowed'\n"
        "controller.polished_roots(den=tiny) -> ValueError not naming den: 'negative dimension"
        "s are not allowed'\n"
        "controller.polished_roots(den=bigint) -> ValueError not naming den: 'negative dimensi"
        "ons are not allowed'\n"
        "controller.polished_roots(den=2d) -> ValueError not naming den: 'could not broadcast "
        "input array from shape (2,3) into shape (8,)'\n"
        "controller.polished_roots(den=empty) -> ValueError not naming den: 'negative dimensio"
        "ns are not allowed'\n"
        "controller.polished_roots(den=nan-array) -> LinAlgError not naming den: 'Array must n"
        "ot contain infs or NaNs'"
    ), False),
    'controller.scan_image:pixel_size': ((
        'controller.scan_image(pixel_size=huge) -> returned non-finite (trace: array with 64 n'
        'on-finite of 64, 64 NaN)'
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
