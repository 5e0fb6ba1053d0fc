"""archquake.validation"""
