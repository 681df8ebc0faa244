"""Known failures of the bad-input campaign (tests/test_api_campaign.py), as strict xfails.

``"module.callable:parameter"`` -> (what fails, slow): each call listed fails today (written by
``python tests/api_campaign_record.py`` from a run of the campaign, then read). Fix them and delete
the entry (strict: a fixed entry turns the run red until it is deleted). ``slow`` marks an entry
whose calls hang until the campaign's 10 s alarm. ``"module.callable:*"`` is the hypothesis search
over random numbers for that callable (its first failing example).
"""

KNOWN = {
    'hardware.ad2.AnalogDiscovery2.open:device_index': ((
        'hardware.ad2.AnalogDiscovery2.open(device_index=nan) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2.open(device_index=None) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2.open(device_index=str) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2.open(device_index=bool) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2.open(device_index=complex) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2.open(device_index=object) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2.open(device_index=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.AnalogDiscovery2:dwf': ((
        'hardware.ad2.AnalogDiscovery2(dwf=nan) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2(dwf=str) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2(dwf=bool) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2(dwf=complex) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2(dwf=object) -> accepted silently\n'
        'hardware.ad2.AnalogDiscovery2(dwf=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary.open:config_index': ((
        'hardware.ad2.SimulatedDwfLibrary.open(config_index=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(config_index=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(config_index=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(config_index=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(config_index=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(config_index=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary.open:device_index': ((
        'hardware.ad2.SimulatedDwfLibrary.open(device_index=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(device_index=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(device_index=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(device_index=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(device_index=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(device_index=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary.open(device_index=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:ad630_gain': ((
        'hardware.ad2.SimulatedDwfLibrary(ad630_gain=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_gain=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_gain=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_gain=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_gain=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_gain=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_gain=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:ad630_order': ((
        'hardware.ad2.SimulatedDwfLibrary(ad630_order=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_order=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_order=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_order=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_order=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_order=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_order=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:ad630_time_constant': ((
        'hardware.ad2.SimulatedDwfLibrary(ad630_time_constant=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_time_constant=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_time_constant=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_time_constant=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_time_constant=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_time_constant=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(ad630_time_constant=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:amplifier_gain': ((
        'hardware.ad2.SimulatedDwfLibrary(amplifier_gain=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(amplifier_gain=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(amplifier_gain=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(amplifier_gain=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(amplifier_gain=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(amplifier_gain=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(amplifier_gain=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:devices': ((
        'hardware.ad2.SimulatedDwfLibrary(devices=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(devices=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(devices=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(devices=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(devices=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(devices=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(devices=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:noise': ((
        'hardware.ad2.SimulatedDwfLibrary(noise=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(noise=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(noise=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(noise=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(noise=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(noise=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:probe': ((
        'hardware.ad2.SimulatedDwfLibrary(probe=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(probe=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(probe=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(probe=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(probe=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(probe=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:reference_pins': ((
        'hardware.ad2.SimulatedDwfLibrary(reference_pins=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(reference_pins=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(reference_pins=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(reference_pins=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(reference_pins=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(reference_pins=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(reference_pins=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.SimulatedDwfLibrary:seed': ((
        'hardware.ad2.SimulatedDwfLibrary(seed=nan) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(seed=None) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(seed=str) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(seed=bool) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(seed=complex) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(seed=object) -> accepted silently\n'
        'hardware.ad2.SimulatedDwfLibrary(seed=nan-array) -> accepted silently'
    ), False),
    'hardware.ad2.library_or_simulation:factory': ((
        'hardware.ad2.library_or_simulation(factory=nan) -> TypeError not naming factory: '
        '"\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=inf) -> TypeError not naming factory: '
        '"\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=-inf) -> TypeError not naming factory:'
        ' "\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=str) -> TypeError not naming factory: '
        '"\'str\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=bool) -> TypeError not naming factory:'
        ' "\'bool\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=complex) -> TypeError not naming factory: '
        '"\'complex\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=list) -> TypeError not naming factory:'
        ' "\'list\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=object) -> TypeError not naming factory: "'
        '\'Foreign\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=zero) -> TypeError not naming factory:'
        ' "\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=negative) -> TypeError not naming factory:'
        ' "\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=huge) -> TypeError not naming factory:'
        ' "\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=-huge) -> TypeError not naming factory'
        ': "\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=tiny) -> TypeError not naming factory:'
        ' "\'float\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=bigint) -> TypeError not naming factory: "'
        '\'int\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=hugeint) -> TypeError not naming factory: '
        '"\'int\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=2d) -> TypeError not naming factory: "'
        '\'numpy.ndarray\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=empty) -> TypeError not naming factory'
        ': "\'numpy.ndarray\' object is not callable"\n'
        'hardware.ad2.library_or_simulation(factory=nan-array) -> TypeError not naming factory'
        ': "\'numpy.ndarray\' object is not callable"'
    ), False),
    'hardware.ad2.pattern_timing:clock': ((
        "hardware.ad2.pattern_timing(clock=huge) -> ValueError not naming clock: 'frequency 40"
        "000 Hz is below the slowest square the pattern generator makes, 1.42109e+286 H...'"
    ), False),
    'hardware.ad2.pattern_timing:max_count': ((
        "hardware.ad2.pattern_timing(max_count=hugeint) -> OverflowError: 'int too large to co"
        "nvert to float'"
    ), False),
    'hardware.ad2.pattern_timing:max_divider': ((
        'hardware.ad2.pattern_timing(max_divider=nan) -> accepted silently\n'
        "hardware.ad2.pattern_timing(max_divider=-inf) -> ValueError not naming max_divider: '"
        "frequency 40000 Hz is below the slowest square the pattern generator makes, -0 Hz'..."
        "'\n"
        'hardware.ad2.pattern_timing(max_divider=None) -> TypeError not naming max_divider'
        ': "\'>\' not supported between instances of \'int\' and \'NoneType\'"\n'
        'hardware.ad2.pattern_timing(max_divider=str) -> TypeError not naming max_divider:'
        ' "\'>\' not supported between instances of \'int\' and \'str\'"\n'
        'hardware.ad2.pattern_timing(max_divider=bool) -> accepted silently\n'
        'hardware.ad2.pattern_timing(max_divider=complex) -> TypeError not naming max_divider:'
        ' "\'>\' not supported between instances of \'int\' and \'complex\'"\n'
        'hardware.ad2.pattern_timing(max_divider=list) -> TypeError not naming max_divider'
        ': "\'>\' not supported between instances of \'int\' and \'list\'"\n'
        'hardware.ad2.pattern_timing(max_divider=object) -> TypeError not naming max_divider: '
        '"\'>\' not supported between instances of \'int\' and \'Foreign\'"\n'
        "hardware.ad2.pattern_timing(max_divider=zero) -> ZeroDivisionError: 'float division b"
        "y zero'\n"
        'hardware.ad2.pattern_timing(max_divider=negative) -> ValueError not naming max_divide'
        "r: 'frequency 40000 Hz is below the slowest square the pattern generator makes, -1525"
        ".88 Hz'...'\n"
        'hardware.ad2.pattern_timing(max_divider=-huge) -> ValueError not naming max_divider: '
        "'frequency 40000 Hz is below the slowest square the pattern generator makes, -1.52588"
        "e-297 ...'\n"
        "hardware.ad2.pattern_timing(max_divider=tiny) -> ValueError not naming max_divider: '"
        'frequency 40000 Hz is below the slowest square the pattern generator makes, 1.52588e+'
        "303 H...'\n"
        "hardware.ad2.pattern_timing(max_divider=2d) -> ValueError not naming max_divider: 'Th"
        'e truth value of an array with more than one element is ambiguous. Use a.any() or a.a'
        "ll(...'\n"
        'hardware.ad2.pattern_timing(max_divider=empty) -> ValueError not naming max_divider: '
        "'The truth value of an empty array is ambiguous. Use `array.size > 0` to check that a"
        "n arra...'\n"
        'hardware.ad2.pattern_timing(max_divider=nan-array) -> ValueError not naming max_divid'
        "er: 'The truth value of an array with more than one element is ambiguous. Use a.any()"
        " or a.all(...'"
    ), False),
    'hardware.educational.device.EducationalAFM.set:value': ((
        'hardware.educational.device.EducationalAFM.set(value=nan) -> ValueError not naming va'
        "lue: 'NX (pixels per line) must be an integer 2..512, got nan'\n"
        'hardware.educational.device.EducationalAFM.set(value=inf) -> ValueError not naming va'
        "lue: 'NX (pixels per line) must be an integer 2..512, got inf'\n"
        'hardware.educational.device.EducationalAFM.set(value=-inf) -> ValueError not naming v'
        "alue: 'NX (pixels per line) must be an integer 2..512, got -inf'\n"
        'hardware.educational.device.EducationalAFM.set(value=str) -> ValueError not naming va'
        'lue: "NX (pixels per line) must be an integer 2..512, got \'1e-6\'"\n'
        'hardware.educational.device.EducationalAFM.set(value=bool) -> ValueError not naming v'
        "alue: 'NX (pixels per line) must be an integer 2..512, got True'\n"
        'hardware.educational.device.EducationalAFM.set(value=complex) -> ValueError not namin'
        "g value: 'NX (pixels per line) must be an integer 2..512, got (1+1j)'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=list) -> ValueError not naming v'
        "alue: 'NX (pixels per line) must be an integer 2..512, got [1.0, 2.0]'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=object) -> ValueError not naming'
        " value: 'NX (pixels per line) must be an integer 2..512, got Foreign()'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=zero) -> ValueError not naming v'
        "alue: 'NX (pixels per line) must be an integer 2..512, got 0.0'\n"
        'hardware.educational.device.EducationalAFM.set(value=negative) -> ValueError not nami'
        "ng value: 'NX (pixels per line) must be an integer 2..512, got -1.0'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=huge) -> ValueError not naming v'
        "alue: 'NX (pixels per line) must be an integer 2..512, got 1e+300'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=-huge) -> ValueError not naming '
        "value: 'NX (pixels per line) must be an integer 2..512, got -1e+300'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=tiny) -> ValueError not naming v'
        "alue: 'NX (pixels per line) must be an integer 2..512, got 1e-300'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=bigint) -> ValueError not naming'
        " value: 'NX (pixels per line) must be an integer 2..512, got 1000000000'...'\n"
        'hardware.educational.device.EducationalAFM.set(value=hugeint) -> ValueError not namin'
        "g value: 'NX (pixels per line) must be an integer 2..512, got 10000000000000000000000"
        "000000000000000...'\n"
        'hardware.educational.device.EducationalAFM.set(value=2d) -> ValueError not naming val'
        "ue: 'NX (pixels per line) must be an integer 2..512, got array([[1., 1., 1.],\\n  "
        "     [1., 1., ...'\n"
        'hardware.educational.device.EducationalAFM.set(value=empty) -> ValueError not naming '
        "value: 'NX (pixels per line) must be an integer 2..512, got array([], dtype=float64)'"
        "...'\n"
        'hardware.educational.device.EducationalAFM.set(value=nan-array) -> ValueError not nam'
        "ing value: 'NX (pixels per line) must be an integer 2..512, got array([ 0., nan])'..."
        "'"
    ), False),
    'hardware.educational.device.live_view:scene': ((
        'hardware.educational.device.live_view(scene=nan) -> accepted silently\n'
        'hardware.educational.device.live_view(scene=str) -> accepted silently\n'
        'hardware.educational.device.live_view(scene=bool) -> accepted silently\n'
        'hardware.educational.device.live_view(scene=complex) -> accepted silently\n'
        'hardware.educational.device.live_view(scene=object) -> accepted silently\n'
        'hardware.educational.device.live_view(scene=nan-array) -> accepted silently'
    ), False),
    'hardware.educational.session.EducationalSession.open:server': ((
        'hardware.educational.session.EducationalSession.open(server=nan) -> accepted silently'
        '\n'
        'hardware.educational.session.EducationalSession.open(server=str) -> accepted silently'
        '\n'
        'hardware.educational.session.EducationalSession.open(server=bool) -> accepted silentl'
        'y\n'
        'hardware.educational.session.EducationalSession.open(server=complex) -> accepted sile'
        'ntly\n'
        'hardware.educational.session.EducationalSession.open(server=object) -> accepted silen'
        'tly\n'
        'hardware.educational.session.EducationalSession.open(server=nan-array) -> accepted si'
        'lently'
    ), False),
    'hardware.educational.session.EducationalSession.step:wait': ((
        'hardware.educational.session.EducationalSession.step(wait=nan) -> accepted silently\n'
        'hardware.educational.session.EducationalSession.step(wait=None) -> accepted silen'
        'tly\n'
        'hardware.educational.session.EducationalSession.step(wait=str) -> accepted silently\n'
        'hardware.educational.session.EducationalSession.step(wait=bool) -> accepted silen'
        'tly\n'
        'hardware.educational.session.EducationalSession.step(wait=complex) -> accepted silent'
        'ly\n'
        'hardware.educational.session.EducationalSession.step(wait=object) -> accepted silentl'
        'y\n'
        'hardware.educational.session.EducationalSession.step(wait=nan-array) -> accepted sile'
        'ntly'
    ), False),
    'hardware.educational.session.EducationalSession.twin:scanned': ((
        'hardware.educational.session.EducationalSession.twin(scanned=nan) -> TypeError not na'
        "ming scanned: 'sample must be a Sample, got float nan'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=inf) -> TypeError not na'
        "ming scanned: 'sample must be a Sample, got float inf'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=-inf) -> TypeError not n'
        "aming scanned: 'sample must be a Sample, got float -inf'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=str) -> TypeError not na'
        'ming scanned: "sample must be a Sample, got str \'1e-6\'"\n'
        'hardware.educational.session.EducationalSession.twin(scanned=bool) -> TypeError not n'
        "aming scanned: 'sample must be a Sample, got bool True'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=complex) -> TypeError no'
        "t naming scanned: 'sample must be a Sample, got complex (1+1j)'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=list) -> TypeError not n'
        "aming scanned: 'sample must be a Sample, got list [1.0, 2.0]'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=object) -> TypeError not'
        " naming scanned: 'sample must be a Sample, got Foreign Foreign()'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=zero) -> TypeError not n'
        "aming scanned: 'sample must be a Sample, got float 0.0'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=negative) -> TypeError n'
        "ot naming scanned: 'sample must be a Sample, got float -1.0'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=huge) -> TypeError not n'
        "aming scanned: 'sample must be a Sample, got float 1e+300'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=-huge) -> TypeError not '
        "naming scanned: 'sample must be a Sample, got float -1e+300'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=tiny) -> TypeError not n'
        "aming scanned: 'sample must be a Sample, got float 1e-300'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=bigint) -> TypeError not'
        " naming scanned: 'sample must be a Sample, got int 1000000000'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=hugeint) -> TypeError no'
        "t naming scanned: 'sample must be a Sample, got int 100000000000000000000000000000000"
        "000000000000000000000000...'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=2d) -> TypeError not nam'
        "ing scanned: 'sample must be a Sample, got ndarray array([[1., 1., 1.],\\n       ["
        "1., 1., 1.],\\n       [1...'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=empty) -> TypeError not '
        "naming scanned: 'sample must be a Sample, got ndarray array([], dtype=float64)'...'\n"
        'hardware.educational.session.EducationalSession.twin(scanned=nan-array) -> TypeError '
        "not naming scanned: 'sample must be a Sample, got ndarray array([ 0., nan])'...'"
    ), False),
    'hardware.educational.session.EducationalSession:server': ((
        'hardware.educational.session.EducationalSession(server=nan) -> accepted silently\n'
        'hardware.educational.session.EducationalSession(server=str) -> accepted silently\n'
        'hardware.educational.session.EducationalSession(server=bool) -> accepted silently\n'
        'hardware.educational.session.EducationalSession(server=complex) -> accepted silen'
        'tly\n'
        'hardware.educational.session.EducationalSession(server=object) -> accepted silently\n'
        'hardware.educational.session.EducationalSession(server=nan-array) -> accepted silentl'
        'y'
    ), False),
    'hardware.educational.twin.EducationalAFMTwin.error:word': ((
        'hardware.educational.twin.EducationalAFMTwin.error(word=str) -> accepted silently'
    ), False),
    'hardware.educational.twin.EducationalAFMTwin:fault_at': ((
        'hardware.educational.twin.EducationalAFMTwin(fault_at=nan) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(fault_at=str) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(fault_at=bool) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(fault_at=complex) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(fault_at=object) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(fault_at=nan-array) -> accepted silently'
    ), False),
    'hardware.educational.twin.EducationalAFMTwin:noise': ((
        'hardware.educational.twin.EducationalAFMTwin(noise=nan) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(noise=None) -> TypeError not naming nois'
        'e: "float() argument must be a string or a real number, not \'NoneType\'"...\'\n'
        'hardware.educational.twin.EducationalAFMTwin(noise=str) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(noise=bool) -> accepted silently\n'
        'hardware.educational.twin.EducationalAFMTwin(noise=complex) -> TypeError not naming n'
        'oise: "float() argument must be a string or a real number, not \'complex\'"...\'\n'
        'hardware.educational.twin.EducationalAFMTwin(noise=list) -> TypeError not naming nois'
        'e: "float() argument must be a string or a real number, not \'list\'"...\'\n'
        'hardware.educational.twin.EducationalAFMTwin(noise=object) -> TypeError not naming no'
        'ise: "float() argument must be a string or a real number, not \'Foreign\'"...\'\n'
        "hardware.educational.twin.EducationalAFMTwin(noise=hugeint) -> OverflowError: 'int to"
        "o large to convert to float'\n"
        'hardware.educational.twin.EducationalAFMTwin(noise=2d) -> TypeError not naming noise:'
        " 'only 0-dimensional arrays can be converted to Python scalars'\n"
        'hardware.educational.twin.EducationalAFMTwin(noise=empty) -> TypeError not naming noi'
        "se: 'only 0-dimensional arrays can be converted to Python scalars'...'\n"
        'hardware.educational.twin.EducationalAFMTwin(noise=nan-array) -> TypeError not naming'
        " noise: 'only 0-dimensional arrays can be converted to Python scalars'...'"
    ), False),
    'hardware.experiments.ad2_reading:dwf': ((
        'hardware.experiments.ad2_reading(dwf=nan) -> AttributeError: "\'float\' object has '
        'no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=inf) -> AttributeError: "\'float\' object has '
        'no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=-inf) -> AttributeError: "\'float\' object has'
        ' no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=str) -> AttributeError: "\'str\' object has no'
        ' attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=bool) -> AttributeError: "\'bool\' object has '
        'no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=complex) -> AttributeError: "\'complex\' objec'
        't has no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=list) -> AttributeError: "\'list\' object has '
        'no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=object) -> AttributeError: "\'Foreign\' object'
        ' has no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=zero) -> AttributeError: "\'float\' object has'
        ' no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=negative) -> AttributeError: "\'float\' object'
        ' has no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=huge) -> AttributeError: "\'float\' object has'
        ' no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=-huge) -> AttributeError: "\'float\' object ha'
        's no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=tiny) -> AttributeError: "\'float\' object has'
        ' no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=bigint) -> AttributeError: "\'int\' object has'
        ' no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=hugeint) -> AttributeError: "\'int\' object ha'
        's no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=2d) -> AttributeError: "\'numpy.ndarray\' obje'
        'ct has no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=empty) -> AttributeError: "\'numpy.ndarray\' o'
        'bject has no attribute \'deviceControl\'"\n'
        'hardware.experiments.ad2_reading(dwf=nan-array) -> AttributeError: "\'numpy.ndarra'
        'y\' object has no attribute \'deviceControl\'"'
    ), False),
    'hardware.haptic.bridge.CantileverSource.force:position': ((
        'hardware.haptic.bridge.CantileverSource.force(position=nan) -> accepted silently\n'
        'hardware.haptic.bridge.CantileverSource.force(position=str) -> TypeError not naming p'
        'osition: "can\'t multiply sequence by non-int of type \'float\'"\n'
        'hardware.haptic.bridge.CantileverSource.force(position=bool) -> accepted silently\n'
        'hardware.haptic.bridge.CantileverSource.force(position=complex) -> accepted silen'
        'tly\n'
        'hardware.haptic.bridge.CantileverSource.force(position=list) -> TypeError not naming '
        'position: "can\'t multiply sequence by non-int of type \'float\'"\n'
        'hardware.haptic.bridge.CantileverSource.force(position=object) -> TypeError not namin'
        'g position: "unsupported operand type(s) for *: \'float\' and \'Foreign\'"...\'\n'
        "hardware.haptic.bridge.CantileverSource.force(position=hugeint) -> OverflowError: 'in"
        "t too large to convert to float'\n"
        'hardware.haptic.bridge.CantileverSource.force(position=nan-array) -> accepted silentl'
        'y'
    ), False),
    'hardware.haptic.bridge.CantileverSource.force:time': ((
        'hardware.haptic.bridge.CantileverSource.force(time=nan) -> accepted silently\n'
        'hardware.haptic.bridge.CantileverSource.force(time=str) -> accepted silently\n'
        'hardware.haptic.bridge.CantileverSource.force(time=bool) -> accepted silently\n'
        'hardware.haptic.bridge.CantileverSource.force(time=complex) -> accepted silently\n'
        'hardware.haptic.bridge.CantileverSource.force(time=object) -> accepted silently\n'
        'hardware.haptic.bridge.CantileverSource.force(time=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.ForceBridge.stop:timeout': ((
        'hardware.haptic.bridge.ForceBridge.stop(timeout=nan) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge.stop(timeout=None) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge.stop(timeout=str) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge.stop(timeout=bool) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge.stop(timeout=complex) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge.stop(timeout=object) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge.stop(timeout=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.ForceBridge:clock': ((
        'hardware.haptic.bridge.ForceBridge(clock=nan) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(clock=None) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(clock=str) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(clock=bool) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(clock=complex) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(clock=object) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(clock=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.ForceBridge:max_force': ((
        'hardware.haptic.bridge.ForceBridge(max_force=2d) -> ValueError not naming max_force: '
        "'The truth value of an array with more than one element is ambiguous. Use a.any() or "
        "a.all(...'\n"
        'hardware.haptic.bridge.ForceBridge(max_force=empty) -> ValueError not naming max_forc'
        "e: 'The truth value of an empty array is ambiguous. Use `array.size > 0` to check tha"
        "t an arra...'\n"
        'hardware.haptic.bridge.ForceBridge(max_force=nan-array) -> ValueError not naming max_'
        "force: 'The truth value of an array with more than one element is ambiguous. Use a.an"
        "y() or a.all(...'"
    ), False),
    'hardware.haptic.bridge.ForceBridge:sleep': ((
        'hardware.haptic.bridge.ForceBridge(sleep=nan) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(sleep=None) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(sleep=str) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(sleep=bool) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(sleep=complex) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(sleep=object) -> accepted silently\n'
        'hardware.haptic.bridge.ForceBridge(sleep=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.FunctionSource.force:position': ((
        'hardware.haptic.bridge.FunctionSource.force(position=nan) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(position=str) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(position=bool) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(position=complex) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(position=object) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(position=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.FunctionSource.force:time': ((
        'hardware.haptic.bridge.FunctionSource.force(time=nan) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(time=str) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(time=bool) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(time=complex) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(time=object) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource.force(time=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.FunctionSource:name': ((
        'hardware.haptic.bridge.FunctionSource(name=nan) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource(name=bool) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource(name=complex) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource(name=object) -> accepted silently\n'
        'hardware.haptic.bridge.FunctionSource(name=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.GaugeSource.force:position': ((
        'hardware.haptic.bridge.GaugeSource.force(position=nan) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(position=str) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(position=bool) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(position=complex) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(position=object) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(position=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.GaugeSource.force:time': ((
        'hardware.haptic.bridge.GaugeSource.force(time=nan) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(time=str) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(time=bool) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(time=complex) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(time=object) -> accepted silently\n'
        'hardware.haptic.bridge.GaugeSource.force(time=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.IndentationSource.force:position': ((
        'hardware.haptic.bridge.IndentationSource.force(position=nan) -> accepted silently\n'
        'hardware.haptic.bridge.IndentationSource.force(position=str) -> TypeError not naming '
        'position: "unsupported operand type(s) for -: \'str\' and \'float\'"\n'
        'hardware.haptic.bridge.IndentationSource.force(position=bool) -> accepted silently\n'
        'hardware.haptic.bridge.IndentationSource.force(position=complex) -> TypeError not nam'
        'ing position: "\'<=\' not supported between instances of \'complex\' and \'float\'"'
        "...'\n"
        'hardware.haptic.bridge.IndentationSource.force(position=list) -> TypeError not naming'
        ' position: "unsupported operand type(s) for -: \'list\' and \'float\'"...\'\n'
        'hardware.haptic.bridge.IndentationSource.force(position=object) -> TypeError not nami'
        'ng position: "unsupported operand type(s) for -: \'Foreign\' and \'float\'"...\'\n'
        "hardware.haptic.bridge.IndentationSource.force(position=hugeint) -> OverflowError: 'i"
        "nt too large to convert to float'\n"
        'hardware.haptic.bridge.IndentationSource.force(position=2d) -> ValueError not naming '
        "position: 'The truth value of an array with more than one element is ambiguous. Use a"
        ".any() or a.all(...'\n"
        'hardware.haptic.bridge.IndentationSource.force(position=empty) -> ValueError not nami'
        "ng position: 'The truth value of an empty array is ambiguous. Use `array.size > 0` to"
        " check that an arra...'\n"
        'hardware.haptic.bridge.IndentationSource.force(position=nan-array) -> ValueError not '
        "naming position: 'The truth value of an array with more than one element is ambiguous"
        ". Use a.any() or a.all(...'"
    ), False),
    'hardware.haptic.bridge.IndentationSource.force:time': ((
        'hardware.haptic.bridge.IndentationSource.force(time=nan) -> accepted silently\n'
        'hardware.haptic.bridge.IndentationSource.force(time=str) -> accepted silently\n'
        'hardware.haptic.bridge.IndentationSource.force(time=bool) -> accepted silently\n'
        'hardware.haptic.bridge.IndentationSource.force(time=complex) -> accepted silently\n'
        'hardware.haptic.bridge.IndentationSource.force(time=object) -> accepted silently\n'
        'hardware.haptic.bridge.IndentationSource.force(time=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.TappingSource.force:position': ((
        'hardware.haptic.bridge.TappingSource.force(position=nan) -> accepted silently\n'
        'hardware.haptic.bridge.TappingSource.force(position=str) -> accepted silently\n'
        'hardware.haptic.bridge.TappingSource.force(position=bool) -> accepted silently\n'
        'hardware.haptic.bridge.TappingSource.force(position=complex) -> accepted silently\n'
        'hardware.haptic.bridge.TappingSource.force(position=object) -> accepted silently\n'
        'hardware.haptic.bridge.TappingSource.force(position=nan-array) -> accepted silently'
    ), False),
    'hardware.haptic.bridge.TappingSource.force:time': ((
        'hardware.haptic.bridge.TappingSource.force(time=nan) -> accepted silently\n'
        'hardware.haptic.bridge.TappingSource.force(time=inf) -> returned non-finite (nan)\n'
        'hardware.haptic.bridge.TappingSource.force(time=-inf) -> returned non-finite (nan)\n'
        "hardware.haptic.bridge.TappingSource.force(time=str) -> TypeError not naming time: 'n"
        "ot all arguments converted during string formatting'\n"
        'hardware.haptic.bridge.TappingSource.force(time=bool) -> accepted silently\n'
        'hardware.haptic.bridge.TappingSource.force(time=complex) -> TypeError not naming time'
        ': "unsupported operand type(s) for %: \'complex\' and \'float\'"\n'
        'hardware.haptic.bridge.TappingSource.force(time=list) -> TypeError not naming time: "'
        'unsupported operand type(s) for %: \'list\' and \'float\'"\n'
        'hardware.haptic.bridge.TappingSource.force(time=object) -> TypeError not naming time:'
        ' "unsupported operand type(s) for %: \'Foreign\' and \'float\'"\n'
        "hardware.haptic.bridge.TappingSource.force(time=hugeint) -> OverflowError: 'int too l"
        "arge to convert to float'\n"
        "hardware.haptic.bridge.TappingSource.force(time=2d) -> TypeError not naming time: 'on"
        "ly 0-dimensional arrays can be converted to Python scalars'\n"
        'hardware.haptic.bridge.TappingSource.force(time=empty) -> TypeError not naming time: '
        "'only 0-dimensional arrays can be converted to Python scalars'\n"
        'hardware.haptic.bridge.TappingSource.force(time=nan-array) -> TypeError not naming ti'
        "me: 'only 0-dimensional arrays can be converted to Python scalars'...'"
    ), False),
    'hardware.haptic.bridge.TappingSource:distance': ((
        'hardware.haptic.bridge.TappingSource(distance=tiny) -> still running after 10 s of CP'
        'U'
    ), True),
    'hardware.haptic.codec.param_to_wire:value': ((
        "hardware.haptic.codec.param_to_wire(value=nan) -> ValueError not naming value: 'max_f"
        "orce must be a finite number in N, got nan'\n"
        "hardware.haptic.codec.param_to_wire(value=inf) -> ValueError not naming value: 'max_f"
        "orce must be a finite number in N, got inf'\n"
        "hardware.haptic.codec.param_to_wire(value=-inf) -> ValueError not naming value: 'max_"
        "force must be a finite number in N, got -inf'\n"
        'hardware.haptic.codec.param_to_wire(value=str) -> ValueError not naming value: "max_f'
        'orce must be a finite number in N, got \'1e-6\'"\n'
        "hardware.haptic.codec.param_to_wire(value=bool) -> ValueError not naming value: 'max_"
        "force must be a finite number in N, got True'\n"
        "hardware.haptic.codec.param_to_wire(value=complex) -> ValueError not naming value: 'm"
        "ax_force must be a finite number in N, got (1+1j)'\n"
        "hardware.haptic.codec.param_to_wire(value=list) -> ValueError not naming value: 'max_"
        "force must be a finite number in N, got [1.0, 2.0]'\n"
        "hardware.haptic.codec.param_to_wire(value=object) -> ValueError not naming value: 'ma"
        "x_force must be a finite number in N, got Foreign()'\n"
        "hardware.haptic.codec.param_to_wire(value=negative) -> ValueError not naming value: '"
        "max_force must be in [0, 5] N, got -1.0'\n"
        "hardware.haptic.codec.param_to_wire(value=huge) -> ValueError not naming value: 'max_"
        "force must be in [0, 5] N, got 1e+300'\n"
        "hardware.haptic.codec.param_to_wire(value=-huge) -> ValueError not naming value: 'max"
        "_force must be in [0, 5] N, got -1e+300'\n"
        "hardware.haptic.codec.param_to_wire(value=bigint) -> ValueError not naming value: 'ma"
        "x_force must be in [0, 5] N, got 1000000000.0'\n"
        "hardware.haptic.codec.param_to_wire(value=hugeint) -> ValueError not naming value: 'm"
        'ax_force must be a finite number in N, got 100000000000000000000000000000000000000000'
        "0000...'\n"
        "hardware.haptic.codec.param_to_wire(value=2d) -> ValueError not naming value: 'max_fo"
        'rce must be a finite number in N, got array([[1., 1., 1.],\\n       [1., 1., 1.],\\'
        "n  ...'\n"
        "hardware.haptic.codec.param_to_wire(value=empty) -> ValueError not naming value: 'max"
        "_force must be a finite number in N, got array([], dtype=float64)'...'\n"
        'hardware.haptic.codec.param_to_wire(value=nan-array) -> ValueError not naming value: '
        "'max_force must be a finite number in N, got array([ 0., nan])'"
    ), False),
    'hardware.haptic.device.HapticDevice.set:value': ((
        "hardware.haptic.device.HapticDevice.set(value=nan) -> ValueError not naming value: 'm"
        "ax_force must be a finite number in N, got nan'\n"
        "hardware.haptic.device.HapticDevice.set(value=inf) -> ValueError not naming value: 'm"
        "ax_force must be a finite number in N, got inf'\n"
        "hardware.haptic.device.HapticDevice.set(value=-inf) -> ValueError not naming value: '"
        "max_force must be a finite number in N, got -inf'\n"
        'hardware.haptic.device.HapticDevice.set(value=str) -> ValueError not naming value: "m'
        'ax_force must be a finite number in N, got \'1e-6\'"\n'
        "hardware.haptic.device.HapticDevice.set(value=bool) -> ValueError not naming value: '"
        "max_force must be a finite number in N, got True'\n"
        'hardware.haptic.device.HapticDevice.set(value=complex) -> ValueError not naming value'
        ": 'max_force must be a finite number in N, got (1+1j)'\n"
        "hardware.haptic.device.HapticDevice.set(value=list) -> ValueError not naming value: '"
        "max_force must be a finite number in N, got [1.0, 2.0]'\n"
        'hardware.haptic.device.HapticDevice.set(value=object) -> ValueError not naming value:'
        " 'max_force must be a finite number in N, got Foreign()'\n"
        'hardware.haptic.device.HapticDevice.set(value=negative) -> ValueError not naming valu'
        "e: 'max_force must be in [0, 5] N, got -1.0'\n"
        "hardware.haptic.device.HapticDevice.set(value=huge) -> ValueError not naming value: '"
        "max_force must be in [0, 5] N, got 1e+300'\n"
        'hardware.haptic.device.HapticDevice.set(value=-huge) -> ValueError not naming value: '
        "'max_force must be in [0, 5] N, got -1e+300'\n"
        'hardware.haptic.device.HapticDevice.set(value=bigint) -> ValueError not naming value:'
        " 'max_force must be in [0, 5] N, got 1000000000.0'\n"
        'hardware.haptic.device.HapticDevice.set(value=hugeint) -> ValueError not naming value'
        ": 'max_force must be a finite number in N, got 10000000000000000000000000000000000000"
        "00000000...'\n"
        "hardware.haptic.device.HapticDevice.set(value=2d) -> ValueError not naming value: 'ma"
        'x_force must be a finite number in N, got array([[1., 1., 1.],\\n       [1., 1., 1'
        ".],\\n  ...'\n"
        'hardware.haptic.device.HapticDevice.set(value=empty) -> ValueError not naming value: '
        "'max_force must be a finite number in N, got array([], dtype=float64)'...'\n"
        'hardware.haptic.device.HapticDevice.set(value=nan-array) -> ValueError not naming val'
        "ue: 'max_force must be a finite number in N, got array([ 0., nan])'...'"
    ), False),
    'hardware.experiments.haptic_device:port': ((
        'hardware.experiments.haptic_device(port=str) -> TransportClosed: "cannot open serial '
        "port 1e-6: [Errno 2] could not open port 1e-6: [Errno 2] No such file or directory: '1e...'"
    ), False),
    'hardware.haptic.device.open_haptic:port': ((
        'hardware.haptic.device.open_haptic(port=str) -> TransportClosed: "cannot open serial '
        "port 1e-6: [Errno 2] could not open port 1e-6: [Errno 2] No such file o...'"
    ), False),
    'hardware.haptic.twin.HapticTwin.error:word': ((
        'hardware.haptic.twin.HapticTwin.error(word=str) -> accepted silently'
    ), False),
    'hardware.macro.device.MacroAFM.set:value': ((
        "hardware.macro.device.MacroAFM.set(value=nan) -> ValueError not naming value: 'NX (pi"
        "xels per line) must be an integer 1..128, got nan'\n"
        "hardware.macro.device.MacroAFM.set(value=inf) -> ValueError not naming value: 'NX (pi"
        "xels per line) must be an integer 1..128, got inf'\n"
        "hardware.macro.device.MacroAFM.set(value=-inf) -> ValueError not naming value: 'NX (p"
        "ixels per line) must be an integer 1..128, got -inf'\n"
        'hardware.macro.device.MacroAFM.set(value=str) -> ValueError not naming value: "NX (pi'
        'xels per line) must be an integer 1..128, got \'1e-6\'"\n'
        "hardware.macro.device.MacroAFM.set(value=bool) -> ValueError not naming value: 'NX (p"
        "ixels per line) must be an integer 1..128, got True'\n"
        "hardware.macro.device.MacroAFM.set(value=complex) -> ValueError not naming value: 'NX"
        " (pixels per line) must be an integer 1..128, got (1+1j)'\n"
        "hardware.macro.device.MacroAFM.set(value=list) -> ValueError not naming value: 'NX (p"
        "ixels per line) must be an integer 1..128, got [1.0, 2.0]'\n"
        "hardware.macro.device.MacroAFM.set(value=object) -> ValueError not naming value: 'NX "
        "(pixels per line) must be an integer 1..128, got Foreign()'\n"
        "hardware.macro.device.MacroAFM.set(value=zero) -> ValueError not naming value: 'NX (p"
        "ixels per line) must be an integer 1..128, got 0.0'\n"
        "hardware.macro.device.MacroAFM.set(value=negative) -> ValueError not naming value: 'N"
        "X (pixels per line) must be an integer 1..128, got -1.0'\n"
        "hardware.macro.device.MacroAFM.set(value=huge) -> ValueError not naming value: 'NX (p"
        "ixels per line) must be an integer 1..128, got 1e+300'\n"
        "hardware.macro.device.MacroAFM.set(value=-huge) -> ValueError not naming value: 'NX ("
        "pixels per line) must be an integer 1..128, got -1e+300'\n"
        "hardware.macro.device.MacroAFM.set(value=tiny) -> ValueError not naming value: 'NX (p"
        "ixels per line) must be an integer 1..128, got 1e-300'\n"
        "hardware.macro.device.MacroAFM.set(value=bigint) -> ValueError not naming value: 'NX "
        "(pixels per line) must be an integer 1..128, got 1000000000'\n"
        "hardware.macro.device.MacroAFM.set(value=hugeint) -> ValueError not naming value: 'NX"
        ' (pixels per line) must be an integer 1..128, got 10000000000000000000000000000000000'
        "000...'\n"
        "hardware.macro.device.MacroAFM.set(value=2d) -> ValueError not naming value: 'NX (pix"
        'els per line) must be an integer 1..128, got array([[1., 1., 1.],\\n       [1., 1.'
        ", ...'\n"
        "hardware.macro.device.MacroAFM.set(value=empty) -> ValueError not naming value: 'NX ("
        "pixels per line) must be an integer 1..128, got array([], dtype=float64)'...'\n"
        "hardware.macro.device.MacroAFM.set(value=nan-array) -> ValueError not naming value: '"
        "NX (pixels per line) must be an integer 1..128, got array([ 0., nan])'...'"
    ), False),
    'hardware.macro.mechanics.GaugeCalibration.from_weights:free_counts': ((
        'hardware.macro.mechanics.GaugeCalibration.from_weights(free_counts=huge) -> ValueErro'
        "r not naming free_counts: 'counts_per_newton must be in [1, 1e+12] 1/N, got 1.01972e+"
        "301'...'\n"
        'hardware.macro.mechanics.GaugeCalibration.from_weights(free_counts=-huge) -> ValueErr'
        "or not naming free_counts: 'counts_per_newton must be in [1, 1e+12] 1/N, got 1.01972e"
        "+301'...'"
    ), False),
    'hardware.macro.mechanics.GaugeCalibration.from_weights:loaded_counts': ((
        'hardware.macro.mechanics.GaugeCalibration.from_weights(loaded_counts=huge) -> ValueEr'
        "ror not naming loaded_counts: 'counts_per_newton must be in [1, 1e+12] 1/N, got 1.019"
        "72e+301'...'\n"
        'hardware.macro.mechanics.GaugeCalibration.from_weights(loaded_counts=-huge) -> ValueE'
        "rror not naming loaded_counts: 'counts_per_newton must be in [1, 1e+12] 1/N, got 1.01"
        "972e+301'...'"
    ), False),
    'hardware.macro.mechanics.GaugeCalibration.from_weights:mass': ((
        'hardware.macro.mechanics.GaugeCalibration.from_weights(mass=huge) -> ValueError not n'
        "aming mass: 'counts_per_newton must be in [1, 1e+12] 1/N, got 1.01972e-298'...'\n"
        'hardware.macro.mechanics.GaugeCalibration.from_weights(mass=tiny) -> ValueError not n'
        "aming mass: 'counts_per_newton must be in [1, 1e+12] 1/N, got 1.01972e+302'...'\n"
        'hardware.macro.mechanics.GaugeCalibration.from_weights(mass=bigint) -> ValueError not'
        " naming mass: 'counts_per_newton must be in [1, 1e+12] 1/N, got 1.01972e-07'...'"
    ), False),
    'hardware.macro.session.MacroSession.open:server': ((
        'hardware.macro.session.MacroSession.open(server=nan) -> accepted silently\n'
        'hardware.macro.session.MacroSession.open(server=str) -> accepted silently\n'
        'hardware.macro.session.MacroSession.open(server=bool) -> accepted silently\n'
        'hardware.macro.session.MacroSession.open(server=complex) -> accepted silently\n'
        'hardware.macro.session.MacroSession.open(server=object) -> accepted silently\n'
        'hardware.macro.session.MacroSession.open(server=nan-array) -> accepted silently'
    ), False),
    'hardware.macro.session.MacroSession.step:wait': ((
        'hardware.macro.session.MacroSession.step(wait=nan) -> accepted silently\n'
        'hardware.macro.session.MacroSession.step(wait=None) -> accepted silently\n'
        'hardware.macro.session.MacroSession.step(wait=str) -> accepted silently\n'
        'hardware.macro.session.MacroSession.step(wait=bool) -> accepted silently\n'
        'hardware.macro.session.MacroSession.step(wait=complex) -> accepted silently\n'
        'hardware.macro.session.MacroSession.step(wait=object) -> accepted silently\n'
        'hardware.macro.session.MacroSession.step(wait=nan-array) -> accepted silently'
    ), False),
    'hardware.macro.session.MacroSession.twin:scanned': ((
        'hardware.macro.session.MacroSession.twin(scanned=nan) -> TypeError not naming scanned'
        ": 'sample must be a Sample, got float nan'\n"
        'hardware.macro.session.MacroSession.twin(scanned=inf) -> TypeError not naming scanned'
        ": 'sample must be a Sample, got float inf'\n"
        'hardware.macro.session.MacroSession.twin(scanned=-inf) -> TypeError not naming scanne'
        "d: 'sample must be a Sample, got float -inf'\n"
        'hardware.macro.session.MacroSession.twin(scanned=str) -> TypeError not naming scanned'
        ': "sample must be a Sample, got str \'1e-6\'"\n'
        'hardware.macro.session.MacroSession.twin(scanned=bool) -> TypeError not naming scanne'
        "d: 'sample must be a Sample, got bool True'\n"
        'hardware.macro.session.MacroSession.twin(scanned=complex) -> TypeError not naming sca'
        "nned: 'sample must be a Sample, got complex (1+1j)'\n"
        'hardware.macro.session.MacroSession.twin(scanned=list) -> TypeError not naming scanne'
        "d: 'sample must be a Sample, got list [1.0, 2.0]'\n"
        'hardware.macro.session.MacroSession.twin(scanned=object) -> TypeError not naming scan'
        "ned: 'sample must be a Sample, got Foreign Foreign()'\n"
        'hardware.macro.session.MacroSession.twin(scanned=zero) -> TypeError not naming scanne'
        "d: 'sample must be a Sample, got float 0.0'\n"
        'hardware.macro.session.MacroSession.twin(scanned=negative) -> TypeError not naming sc'
        "anned: 'sample must be a Sample, got float -1.0'\n"
        'hardware.macro.session.MacroSession.twin(scanned=huge) -> TypeError not naming scanne'
        "d: 'sample must be a Sample, got float 1e+300'\n"
        'hardware.macro.session.MacroSession.twin(scanned=-huge) -> TypeError not naming scann'
        "ed: 'sample must be a Sample, got float -1e+300'\n"
        'hardware.macro.session.MacroSession.twin(scanned=tiny) -> TypeError not naming scanne'
        "d: 'sample must be a Sample, got float 1e-300'\n"
        'hardware.macro.session.MacroSession.twin(scanned=bigint) -> TypeError not naming scan'
        "ned: 'sample must be a Sample, got int 1000000000'\n"
        'hardware.macro.session.MacroSession.twin(scanned=hugeint) -> TypeError not naming sca'
        "nned: 'sample must be a Sample, got int 100000000000000000000000000000000000000000000"
        "000000000000...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=2d) -> TypeError not naming scanned:'
        " 'sample must be a Sample, got ndarray array([[1., 1., 1.],\\n       [1., 1., 1.],"
        "\\n       [1...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=empty) -> TypeError not naming scann'
        "ed: 'sample must be a Sample, got ndarray array([], dtype=float64)'...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=nan-array) -> TypeError not naming s'
        "canned: 'sample must be a Sample, got ndarray array([ 0., nan])'\n"
        'hardware.macro.session.MacroSession.twin(scanned=sample-line) -> ValueError not namin'
        'g scanned: "sample must be an image of heights in m, got shape (16,) in \'m\'"...\'\n'
        'hardware.macro.session.MacroSession.twin(scanned=sample-2-rows) -> ValueError not nam'
        'ing scanned: "tip: at the sample\'s height range (0.002 m) the tip is 5 pixels (0.'
        "0016 m) wide along y, w...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=sample-huge-heights) -> ValueError n'
        'ot naming scanned: "tip: at the sample\'s height range (2e+287 m) the tip is 50000'
        "1 pixels (200 m) wide along x...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=sample-extreme) -> ValueError not na'
        "ming scanned: 'sample heights must span a range a float can hold (1.8e308 m), got -1."
        "7e+308 to 1.7e+308 m...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=sample-tiny-pixels) -> ValueError no'
        't naming scanned: "tip: at the sample\'s height range (0.002 m) the tip is 2199023'
        "255553 pixels (2.19902e-288 ...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=sample-anisotropic) -> ValueError no'
        't naming scanned: "tip: at the sample\'s height range (0.002 m) the tip is 2190890'
        "3 pixels (0.00219089 m) wide...'\n"
        'hardware.macro.session.MacroSession.twin(scanned=sample-volts) -> ValueError not nami'
        'ng scanned: "sample must be an image of heights in m, got shape (16, 16) in \'V\'".'
        "..'"
    ), False),
    'hardware.macro.session.MacroSession:server': ((
        'hardware.macro.session.MacroSession(server=nan) -> accepted silently\n'
        'hardware.macro.session.MacroSession(server=str) -> accepted silently\n'
        'hardware.macro.session.MacroSession(server=bool) -> accepted silently\n'
        'hardware.macro.session.MacroSession(server=complex) -> accepted silently\n'
        'hardware.macro.session.MacroSession(server=object) -> accepted silently\n'
        'hardware.macro.session.MacroSession(server=nan-array) -> accepted silently'
    ), False),
    'hardware.macro.twin.MacroAFMTwin.error:word': ((
        'hardware.macro.twin.MacroAFMTwin.error(word=str) -> accepted silently'
    ), False),
    'hardware.macro.twin.MacroAFMTwin.trigger_limit:at': ((
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=str) -> accepted silently\n'
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=bool) -> TypeError not naming at: "'
        '\'bool\' object is not iterable"\n'
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=complex) -> TypeError not naming at'
        ': "\'complex\' object is not iterable"\n'
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=object) -> TypeError not naming at:'
        ' "\'Foreign\' object is not iterable"\n'
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=bigint) -> TypeError not naming at:'
        ' "\'int\' object is not iterable"\n'
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=hugeint) -> TypeError not naming at'
        ': "\'int\' object is not iterable"\n'
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=2d) -> TypeError not naming at: "un'
        'hashable type: \'numpy.ndarray\'"\n'
        'hardware.macro.twin.MacroAFMTwin.trigger_limit(at=nan-array) -> accepted silently'
    ), False),
    'hardware.macro.twin.MacroAFMTwin:seed': ((
        "hardware.macro.twin.MacroAFMTwin(seed=nan) -> TypeError not naming seed: 'SeedSequenc"
        "e expects int or sequence of ints for entropy not nan'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=inf) -> TypeError not naming seed: 'SeedSequenc"
        "e expects int or sequence of ints for entropy not inf'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=-inf) -> TypeError not naming seed: 'SeedSequen"
        "ce expects int or sequence of ints for entropy not -inf'\n"
        'hardware.macro.twin.MacroAFMTwin(seed=None) -> accepted silently\n'
        "hardware.macro.twin.MacroAFMTwin(seed=str) -> TypeError not naming seed: 'SeedSequenc"
        "e expects int or sequence of ints for entropy not 1e-6'\n"
        'hardware.macro.twin.MacroAFMTwin(seed=bool) -> accepted silently\n'
        "hardware.macro.twin.MacroAFMTwin(seed=complex) -> TypeError not naming seed: 'SeedSeq"
        "uence expects int or sequence of ints for entropy not (1+1j)'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=object) -> TypeError not naming seed: 'SeedSequ"
        "ence expects int or sequence of ints for entropy not Foreign()'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=zero) -> TypeError not naming seed: 'SeedSequen"
        "ce expects int or sequence of ints for entropy not 0.0'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=negative) -> TypeError not naming seed: 'SeedSe"
        "quence expects int or sequence of ints for entropy not -1.0'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=huge) -> TypeError not naming seed: 'SeedSequen"
        "ce expects int or sequence of ints for entropy not 1e+300'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=-huge) -> TypeError not naming seed: 'SeedSeque"
        "nce expects int or sequence of ints for entropy not -1e+300'\n"
        "hardware.macro.twin.MacroAFMTwin(seed=tiny) -> TypeError not naming seed: 'SeedSequen"
        "ce expects int or sequence of ints for entropy not 1e-300'"
    ), False),
}
