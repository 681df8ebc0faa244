"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""

KNOWN = {
    'cantilever.Cantilever.strain:z_b': ((
        "cantilever.Cantilever.strain(z_b=empty) -> ValueError not naming z_b: 'operands could"
        " not be broadcast together with shapes (0,) (11,) '"
    ), False),
    'cantilever.Cantilever.stress:z_b': ((
        "cantilever.Cantilever.stress(z_b=empty) -> ValueError not naming z_b: 'operands could"
        " not be broadcast together with shapes (0,) (11,) '"
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
    'materials.get_material:*': ((
        "materials.get_material(name=0.0) -> TypeError not naming name: 'material must be a ke"
        "y of MATERIALS (str) or a Material, got float 0.0'"
    ), False),
    'materials.get_material:name': ((
        "materials.get_material(name=nan) -> TypeError not naming name: 'material must be a ke"
        "y of MATERIALS (str) or a Material, got float nan'\n"
        "materials.get_material(name=inf) -> TypeError not naming name: 'material must be a ke"
        "y of MATERIALS (str) or a Material, got float inf'\n"
        "materials.get_material(name=-inf) -> TypeError not naming name: 'material must be a k"
        "ey of MATERIALS (str) or a Material, got float -inf'\n"
        'materials.get_material(name=str) -> ValueError not naming name: "material must be one'
        " of ['aluminium', 'gold', 'quartz', 'silicon', 'silicon_dioxide', 'sil...'\n"
        "materials.get_material(name=bool) -> TypeError not naming name: 'material must be a k"
        "ey of MATERIALS (str) or a Material, got bool True'\n"
        "materials.get_material(name=complex) -> TypeError not naming name: 'material must be "
        "a key of MATERIALS (str) or a Material, got complex (1+1j)'\n"
        "materials.get_material(name=list) -> TypeError not naming name: 'material must be a k"
        "ey of MATERIALS (str) or a Material, got list [1.0, 2.0]'\n"
        "materials.get_material(name=object) -> TypeError not naming name: 'material must be a"
        " key of MATERIALS (str) or a Material, got Foreign Foreign()'\n"
        "materials.get_material(name=zero) -> TypeError not naming name: 'material must be a k"
        "ey of MATERIALS (str) or a Material, got float 0.0'\n"
        "materials.get_material(name=negative) -> TypeError not naming name: 'material must be"
        " a key of MATERIALS (str) or a Material, got float -1.0'\n"
        "materials.get_material(name=huge) -> TypeError not naming name: 'material must be a k"
        "ey of MATERIALS (str) or a Material, got float 1e+300'\n"
        "materials.get_material(name=-huge) -> TypeError not naming name: 'material must be a "
        "key of MATERIALS (str) or a Material, got float -1e+300'\n"
        "materials.get_material(name=tiny) -> TypeError not naming name: 'material must be a k"
        "ey of MATERIALS (str) or a Material, got float 1e-300'\n"
        "materials.get_material(name=bigint) -> TypeError not naming name: 'material must be a"
        " key of MATERIALS (str) or a Material, got int 1000000000'\n"
        "materials.get_material(name=2d) -> TypeError not naming name: 'material must be a key"
        " of MATERIALS (str) or a Material, got ndarray array([[1., 1., 1.],\\...'\n"
        "materials.get_material(name=empty) -> TypeError not naming name: 'material must be a "
        "key of MATERIALS (str) or a Material, got ndarray array([], dtype=float...'\n"
        "materials.get_material(name=nan-array) -> TypeError not naming name: 'material must b"
        "e a key of MATERIALS (str) or a Material, got ndarray array([ 0., nan])'...'"
    ), False),
}
