"""archquake.sweeps"""
